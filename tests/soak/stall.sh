#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# stall.sh - the live monitor stopped by the OS mid-stream (SIGSTOP, as a
# loaded vehicle computer, a swap or GC pause does), over real LCM UDP
# multicast on loopback in a private network namespace.  When it runs
# again it reads the socket's backlog in one burst: samples evenly
# stamped, received within microseconds of each other.  Every good sample
# must be accepted, every bad one refused under its own reason.
#
#   sh stall.sh SWAYWATCH FEED SOURCE_DIR WORK_DIR
#
# 14 s of samples at 1 kHz with 3 % garbage (duplicates and out-of-order
# copies among it).  The monitor is stopped for 1 s from the 2nd second;
# for 0.2 s from the 5th and again 50 ms later for 1 s; for 1 s from the
# 8th, while the sensor pauses for half a second (its samples unsent:
# lost by seq); and for 1 s from the 11th, while the sensor's clock leaps
# 0.2 s ahead.  Exit 77 (skipped) when no network namespace can be made.
set -eu
SW=$1
FEED=$2
SRC=$3
WORK=$4
RATE=1000

. "$(dirname "$0")/lcmtest.sh"
enter_netns "$@"
rm -rf "$WORK"
mkdir -p "$WORK"
# 16 MiB: a stall of a second at 1 kHz stays in the socket, none dropped
URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=16777216"
MON=""
cleanup() {
    if [ -n "$MON" ]; then
        kill -CONT "$MON" 2>/dev/null || true
        kill "$MON" 2>/dev/null || true
    fi
}
trap cleanup EXIT

# --max-backlog: a stalled monitor must read its backlog, not shed it
"$SW" monitor --scene "$SRC/tests/scenes/crate-a-bare.ini" --lcm-url "$URL" --state-rate 50 \
    --status 1 --max-backlog 30 2>"$WORK/monitor.err" &
MON=$!
wait_subscribed "$WORK/monitor.err"
kill -0 "$MON" || {
    cat "$WORK/monitor.err" >&2
    echo "FAIL: the monitor did not start" >&2
    exit 1
}

utime=$(($(date +%s) * 1000000))
"$FEED" publish "$URL" --count 14000 --rate "$RATE" --garbage 30 --utime0 "$utime" --seed 3 \
    --event 8300:pause:0.5 --event 11300:step:0.2 >"$WORK/feed.txt" &
FEEDER=$!
# stop STOP_AT SECONDS: the monitor stopped SECONDS from STOP_AT s after
# the feeder started
start=$(date +%s.%N)
stop() {
    sleep "$(echo "$start $1 $(date +%s.%N)" | awk '{ d = $1 + $2 - $3; print (d > 0 ? d : 0) }')"
    kill -STOP "$MON"
    echo "stop $(date +%s%6N) $2" >>"$WORK/stops.txt"
    sleep "$2"
    kill -CONT "$MON"
}
stop 2 1
stop 5 0.2
sleep 0.05
kill -STOP "$MON"
sleep 1
kill -CONT "$MON"
stop 8 1
stop 11 1
wait "$FEEDER"
wait_idle "$WORK/monitor.err"
kill -INT "$MON"
set +e
wait "$MON"
mon_rc=$?
set -e
MON=""
udp_drops=$(awk '/^Udp:/ && ++n == 2 { print $6 + $4 }' /proc/net/snmp)

python3 - "$WORK" "$mon_rc" "$udp_drops" "$PROBES" <<'PY'
import re, sys
work, mon_rc, drops, probes = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
sent = {"published": probes, "decode": probes}
for l in open(work + "/feed.txt"):
    f = l.split()
    if len(f) == 2 and f[0] != "last_utime":
        sent[f[0]] = sent.get(f[0], 0) + int(f[1])
err = open(work + "/monitor.err").read()
m = re.search(r"received (\d+) = accepted (\d+) \+ rejected (\d+)(?: \(([^)]*)\))?; "
              r"lost (\d+) \(by seq\)", err)
problems = []
if mon_rc != 0:
    problems.append("monitor exit status %d, expected 0" % mon_rc)
if not m:
    problems.append("no final summary from the monitor")
else:
    received, accepted = int(m.group(1)), int(m.group(2))
    by = {}
    for part in (m.group(4) or "").split(", "):
        if part:
            name, n = part.rsplit(" ", 1)
            by[name] = int(n)
    print("published %d (good %d), received %d, accepted %d, rejected %s, lost %s; "
          "kernel UDP drops %d" % (sent["published"], sent["good"], received, accepted, by,
                                   m.group(5), drops))
    if received != sent["published"]:
        problems.append("received %d of %d published (kernel UDP drops %d): the stall "
                        "outgrew the socket buffer" % (received, sent["published"], drops))
    elif accepted != sent["good"]:
        problems.append("accepted %d of %d good samples" % (accepted, sent["good"]))
    if int(m.group(5)) != sent["skipped"]:
        problems.append("lost %s by seq, the sensor's pause skipped %d" % (m.group(5),
                                                                          sent["skipped"]))
    for reason in set(by) | {"duplicate", "out_of_order", "nonfinite", "implausible"}:
        if by.get(reason, 0) != sent.get(reason, 0):
            problems.append("rejected as %s: %d, sent %d" % (reason, by.get(reason, 0),
                                                             sent.get(reason, 0)))
for p in problems:
    print("FAIL: " + p)
sys.exit(1 if problems else 0)
PY
