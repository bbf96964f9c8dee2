#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Integration, real LCM tools over UDP multicast: lcm-logplayer replays a
# logged accel channel in real time into a running monitor, lcm-logger
# records what the monitor publishes; it must be what `swaywatch replay` of
# the same log publishes: same peak theta, same alarm sequence.
# usage: udpm_logplayer.sh SWAYWATCH SW_LCM_TOOL SCENE PORT
set -eu
. "$(dirname "$0")/netns.sh"
SW=$1 TOOL=$2 SCENE=$3 PORT=$4
URL="udpm://239.255.76.67:$PORT?ttl=0"

"$TOOL" mklog "$T/accel.lcmlog" --rate 500 --duration 3
lcm-logger -q -f -c 'SWAY_.*' --lcm-url="$URL" "$T/rec.lcmlog" &
LOGGER=$!
PIDS="$LOGGER"
# The log's utime is from 2023: no --max-skew for a replayed log.
"$SW" monitor -l "$URL" --scene "$SCENE" --status 1 2>"$T/monitor.err" &
MON=$!
PIDS="$PIDS $MON"
wait_subscribed 4 # the logger and the monitor
lcm-logplayer --lcm-url="$URL" "$T/accel.lcmlog"
wait_for "$T/monitor.err" 'accepted 1501, rejected 0'
sleep 0.4 # the logger's last messages
kill -INT "$MON"
wait "$MON" || fail "monitor exited with $?"
kill -INT "$LOGGER"
wait "$LOGGER" || true
cat "$T/monitor.err"
grep -q 'received 1501 = accepted 1501 + rejected 0; lost 0' "$T/monitor.err" ||
    fail "monitor counts"

"$TOOL" dump "$T/rec.lcmlog" >"$T/live.txt"
replay_published "$T/accel.lcmlog"

grep -q '^state crate-A count 1501 ' "$T/live.txt" || fail "not one state per sample"
grep -q '^nonfinite 0$' "$T/live.txt" || fail "non-finite value published"
same_physics '^alarm .* 1 0 corner lifted' "the pulse should rock the crate"
echo "ok: lcm-logplayer into the monitor == replay of the log (peak theta $peak rad)"
