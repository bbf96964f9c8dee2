#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# soak.sh - the live monitor under a long stream with garbage in it, over
# real LCM UDP multicast on loopback, in a private network namespace.
#
#   sh soak.sh SWAYWATCH FEED SOURCE_DIR WORK_DIR [RUNS GOOD_PER_RUN RATE GARBAGE]
#
# FEED is sw_accel_feed.  The publisher is started RUNS times (default 5),
# each time with GOOD_PER_RUN good samples (default 200000) paced at RATE
# samples per second (default 8000) and GARBAGE bad messages per 1000 good
# ones (default 30: every kind the monitor tells apart), continuing the
# sample clock across its restarts; lcm-logger records the monitor's
# output.  Then the monitor is stopped with SIGINT and:
#   - it must have run to the end and exit 0 (no crash);
#   - every message must be accounted for: published = received =
#     accepted + rejected, accepted = good samples sent, rejected by reason
#     = bad messages sent of that kind, no sample lost (by seq), one seq
#     restart per publisher restart;
#   - its memory must stay flat: VmRSS at the end within SOAK_RSS_KB
#     (default 4096 kB: LCM's receive ring may double once when the machine
#     stalls, a leak grows with the run) of VmRSS after the first run;
#   - a stall of the machine over --max-backlog makes the monitor shed
#     messages: counted as overload, the only good samples it may miss;
#   - no published state or alarm may carry a non-finite number.
# Exit 77 (skipped) when a private network namespace cannot be made.
set -eu
SW=$1
FEED=$2
SRC=$3
WORK=$4
RUNS=${5:-5}
GOOD=${6:-200000}
RATE=${7:-8000}
GARBAGE=${8:-30}
RSS_BOUND=${SOAK_RSS_KB:-4096}

. "$(dirname "$0")/lcmtest.sh"
enter_netns "$@"
rm -rf "$WORK"
mkdir -p "$WORK"
# A receive buffer of 2 MiB absorbs scheduling hiccups of the monitor.
URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"
SCENES="--scene $SRC/tests/scenes/crate-a-bare.ini --scene $SRC/tests/scenes/crate-a-frame.ini"
MON=""
LOGGER=""
cleanup() {
    [ -n "$MON" ] && kill "$MON" 2>/dev/null || true
    [ -n "$LOGGER" ] && kill "$LOGGER" 2>/dev/null || true
}
trap cleanup EXIT

# shellcheck disable=SC2086
"$SW" monitor $SCENES --lcm-url "$URL" --state-rate 50 --status 1 2>"$WORK/monitor.err" &
MON=$!
lcm-logger --lcm-url="$URL" -c 'SWAY_.*' -q "$WORK/output.lcmlog" 2>"$WORK/logger.err" &
LOGGER=$!
wait_subscribed "$WORK/monitor.err"
kill -0 "$MON" || {
    cat "$WORK/monitor.err" >&2
    echo "FAIL: the monitor did not start" >&2
    exit 1
}

# Sample time starts at the wall clock, as from a sensor with a synchronised clock.
utime=$(($(date +%s) * 1000000))
rss_warm=""
i=1
while [ "$i" -le "$RUNS" ]; do
    "$FEED" publish "$URL" --count "$GOOD" --rate "$RATE" --garbage "$GARBAGE" \
        --utime0 "$utime" --seed "$i" >"$WORK/feed-$i.txt"
    last=$(awk '$1 == "last_utime" { print $2 }' "$WORK/feed-$i.txt")
    # The next publisher starts half a second of sample time later, seq at 0.
    utime=$((last + 500000))
    sleep 0.3
    kill -0 "$MON" || {
        cat "$WORK/monitor.err" >&2
        echo "FAIL: the monitor died during run $i" >&2
        exit 1
    }
    rss=$(rss_kb "$MON")
    echo "run $i: $(awk '$1 == "published" { print $2 }' "$WORK/feed-$i.txt") messages, monitor VmRSS $rss kB"
    [ -z "$rss_warm" ] && rss_warm=$rss
    i=$((i + 1))
done
wait_idle "$WORK/monitor.err"
rss_end=$(rss_kb "$MON")
udp_drops=$(awk '/^Udp:/ && ++n == 2 { print $6 + $4 }' /proc/net/snmp)
kill -INT "$MON"
set +e
wait "$MON"
mon_rc=$?
set -e
MON=""
kill -INT "$LOGGER" 2>/dev/null || true
wait "$LOGGER" 2>/dev/null || true
LOGGER=""
"$FEED" check "$WORK/output.lcmlog" >"$WORK/output.txt"

python3 - "$WORK" "$RUNS" "$mon_rc" "$rss_warm" "$rss_end" "$RSS_BOUND" "$udp_drops" "$PROBES" <<'PY'
import re, sys
work, runs, mon_rc, warm, end, bound, drops, probes = sys.argv[1], int(sys.argv[2]), \
    int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6]), int(sys.argv[7]), \
    int(sys.argv[8])
def kv(path):
    return {l.split()[0]: int(l.split()[1]) for l in open(path) if len(l.split()) == 2}
# The probes that found the monitor listening count as received decode errors.
sent = {"published": probes, "decode": probes}
for i in range(1, runs + 1):
    for k, v in kv("%s/feed-%d.txt" % (work, i)).items():
        if k != "last_utime":
            sent[k] = sent.get(k, 0) + v
err = open(work + "/monitor.err").read()
m = re.search(r"received (\d+) = accepted (\d+) \+ rejected (\d+)(?: \(([^)]*)\))?; "
              r"lost (\d+) \(by seq\), seq restarts (\d+)", err)
problems = []
if mon_rc != 0:
    problems.append("monitor exit status %d, expected 0" % mon_rc)
if not m:
    problems.append("no final summary from the monitor")
else:
    received, accepted, rejected = int(m.group(1)), int(m.group(2)), int(m.group(3))
    by = {}
    for part in (m.group(4) or "").split(", "):
        if part:
            name, n = part.rsplit(" ", 1)
            by[name] = int(n)
    lost, restarts = int(m.group(5)), int(m.group(6))
    print("published %d (good %d), received %d = accepted %d + rejected %d %s; lost %d, "
          "seq restarts %d; kernel UDP drops %d"
          % (sent["published"], sent["good"], received, accepted, rejected, by, lost, restarts,
             drops))
    if received != sent["published"]:
        problems.append("received %d of %d published (kernel UDP drops %d)"
                        % (received, sent["published"], drops))
    if received != accepted + rejected or rejected != sum(by.values()):
        problems.append("received != accepted + sum of rejected by reason")
    # a machine that stalls for over a second makes the monitor shed
    # (overload, counted): those are the only good samples it may miss
    shed = by.get("overload", 0)
    if not (0 <= sent["good"] - accepted <= shed):
        problems.append("accepted %d, good samples sent %d, shed %d" % (accepted, sent["good"],
                                                                        shed))
    for reason in ("decode", "trailing", "nonfinite", "implausible", "duplicate", "out_of_order"):
        if by.get(reason, 0) != sent.get(reason, 0):
            problems.append("rejected as %s: %d, sent %d" % (reason, by.get(reason, 0),
                                                             sent.get(reason, 0)))
    if set(by) - set(sent) - {"overload"}:
        problems.append("rejections for reasons never sent: %s" % sorted(set(by) - set(sent)))
    if not (0 <= lost <= shed):
        problems.append("%d samples lost by seq (shed %d)" % (lost, shed))
    if restarts != runs - 1:
        problems.append("%d seq restarts, expected %d" % (restarts, runs - 1))
print("monitor VmRSS: %d kB after the first run, %d kB at the end" % (warm, end))
if end > warm + bound:
    problems.append("memory grew by %d kB (bound %d kB)" % (end - warm, bound))
out = kv(work + "/output.txt")
print("published by the monitor: %d states, %d alarms" % (out["states"], out["alarms"]))
if out["nonfinite"] or out["undecodable"]:
    problems.append("monitor output: %d non-finite numbers, %d undecodable messages"
                    % (out["nonfinite"], out["undecodable"]))
if out["states"] == 0 or out["alarms"] == 0:
    problems.append("the monitor published no states or no alarms")
for p in problems:
    print("FAIL: " + p)
sys.exit(1 if problems else 0)
PY
