#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# memcheck-lcm.sh - the LCM side of the command under valgrind memcheck:
# replay of an lcm-logger file with every kind of bad message in it, and a
# short live monitor run over UDP multicast on loopback in a private
# network namespace, stopped by SIGINT.
#
#   sh memcheck-lcm.sh SWAYWATCH FEED SOURCE_DIR WORK_DIR
#
# FEED is sw_accel_feed.  Exit 77 (skipped) without valgrind or without a
# network namespace.
set -eu
SW=$1
FEED=$2
SRC=$3
WORK=$4
command -v valgrind >/dev/null 2>&1 || {
    echo "valgrind not found: skipped"
    exit 77
}
. "$(dirname "$0")/../soak/lcmtest.sh"
enter_netns "$@"
rm -rf "$WORK"
mkdir -p "$WORK"
VG="valgrind -q --error-exitcode=99 --suppressions=$(dirname "$0")/lcm.supp --leak-check=full
    --show-leak-kinds=definite,indirect,possible
    --errors-for-leak-kinds=definite,indirect,possible --track-origins=yes"
SCENES="--scene $SRC/tests/scenes/crate-a-bare.ini --scene $SRC/tests/scenes/crate-a-frame.ini"
status=0
MON=""
trap '[ -n "$MON" ] && kill "$MON" 2>/dev/null' EXIT

"$FEED" log "$WORK/garbage.lcmlog" --count 5000 --garbage 100 --rate 1000 >"$WORK/feed-log.txt"
set +e
# shellcheck disable=SC2086
$VG "$SW" replay "$WORK/garbage.lcmlog" $SCENES --max-rejected 100 --json >"$WORK/replay.out" 2>"$WORK/replay.err"
rc=$?
set -e
if [ "$rc" -ne 0 ]; then
    echo "FAIL replay of an lcm-logger file: exit $rc" >&2
    grep -v '^swaywatch: ' "$WORK/replay.err" | head -60 >&2
    status=1
else
    echo "ok   replay-lcmlog"
fi

# Under valgrind the monitor runs some 50 times slower: a gentle rate, few
# states, and a receive buffer for the bursts.
URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"
# shellcheck disable=SC2086
$VG "$SW" monitor $SCENES --lcm-url "$URL" --state-rate 20 --status 1 2>"$WORK/monitor.err" &
MON=$!
wait_subscribed "$WORK/monitor.err"
"$FEED" publish "$URL" --count 1500 --rate 200 --garbage 100 >"$WORK/feed-live.txt"
wait_idle "$WORK/monitor.err"
kill -INT "$MON"
set +e
wait "$MON"
rc=$?
set -e
MON=""
if [ "$rc" -ne 0 ]; then
    echo "FAIL monitor: exit $rc" >&2
    grep -v '^swaywatch: ' "$WORK/monitor.err" | head -60 >&2
    status=1
elif ! grep -q "received $(($(awk '$1 == "published" { print $2 }' "$WORK/feed-live.txt") + PROBES)) = accepted" \
    "$WORK/monitor.err"; then
    echo "FAIL monitor: it did not receive every message" >&2
    tail -5 "$WORK/monitor.err" >&2
    status=1
else
    echo "ok   monitor"
fi
exit $status
