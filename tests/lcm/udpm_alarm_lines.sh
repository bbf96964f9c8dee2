#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Alarms on stderr, where people see them: lcm-logplayer plays a braking
# pulse (a log stamped in 2023) into three monitors at once:
#   J: stderr is a file and JOURNAL_STREAM names that file's device:inode,
#      as systemd sets it when stderr is the journal;
#   P: no JOURNAL_STREAM;
#   W: JOURNAL_STREAM names J's file, not its own stderr.
# Every alarm the monitor raised (as many as its summary counts) must be one
# line "swaywatch: alarm TIME level=... package=... kind=... theta=...
# margin=... [reserve_g=...] text=..."; TIME is the wall clock (now, not the log's 2023),
# ISO 8601 UTC with ms.  J's lines start with the syslog priority of their
# level (<2> critical, <4> warn, <6> info), P's and W's with nothing; the
# three saw the same physics alarms.  An error under JOURNAL_STREAM is <3>.
# usage: udpm_alarm_lines.sh SWAYWATCH SW_LCM_TOOL SCENE PORT
set -eu
# Without a network namespace: skipped (77), saying so.
NETNS_SKIP=1
export NETNS_SKIP
. "$(dirname "$0")/netns.sh"
SW=$1 TOOL=$2 SCENE=$3 PORT=$4
URL="udpm://239.255.76.67:$PORT?ttl=0&recv_buf_size=2097152"

devino() { stat -c '%d:%i' "$1"; }
: >"$T/J.err"
: >"$T/W.err"
JS=$(devino "$T/J.err")

"$TOOL" mklog "$T/accel.lcmlog" --rate 500 --duration 3
JOURNAL_STREAM=$JS "$SW" monitor -l "$URL" --scene "$SCENE" 2>>"$T/J.err" &
PIDS="$PIDS $!"
J=$!
"$SW" monitor -l "$URL" --scene "$SCENE" 2>"$T/P.err" &
PIDS="$PIDS $!"
P=$!
JOURNAL_STREAM=$JS "$SW" monitor -l "$URL" --scene "$SCENE" 2>>"$T/W.err" &
PIDS="$PIDS $!"
W=$!
wait_subscribed 6
lcm-logplayer --lcm-url="$URL" "$T/accel.lcmlog"
for m in J P W; do wait_for "$T/$m.err" 'kind=sensor_gap'; done
kill -INT "$J" "$P" "$W"
for p in "$J" "$P" "$W"; do wait "$p" || fail "a monitor exited with $?"; done
cat "$T/J.err"

python3 - "$T" <<'PY' || fail "alarm lines (above)"
import calendar, re, sys, time
T = sys.argv[1]
now = time.time()
line_re = re.compile(
    r'^(<[0-9]>)?swaywatch: alarm (\d{4})-(\d\d)-(\d\d)T(\d\d):(\d\d):(\d\d)\.(\d{3})Z '
    r'level=(info|warn|critical) package=(\S+) kind=([a-z_]+) '
    r'theta=(-|-?\d+\.\d{4}) margin=(-|-?\d+\.\d{4})( reserve_g=\d+\.\d{3})? '
    r'text="([^"]*)"$')
prio = {"critical": "<2>", "warn": "<4>", "info": "<6>"}
def check(cond, what):
    if not cond:
        sys.exit("udpm_alarm_lines.sh: " + what)
physics = {}
for m in "JPW":
    text = open("%s/%s.err" % (T, m)).read().splitlines()
    alarms = [l for l in text if "swaywatch: alarm " in l]
    summary = [l for l in text if "monitor stopped" in l]
    check(len(summary) == 1, m + ": no summary")
    n = int(re.search(r", (\d+) alarms \(", summary[0]).group(1))
    check(len(alarms) == n, "%s: %d alarm lines, the summary counts %d" % (m, len(alarms), n))
    phys = []
    for l in alarms:
        x = line_re.match(l)
        check(x, "%s: not an alarm line: %r" % (m, l))
        g = x.groups()
        t = calendar.timegm(tuple(int(v) for v in g[1:7])) + int(g[7]) / 1e3
        check(abs(t - now) < 120, "%s: %s is not the wall clock" % (m, l))
        level, pkg, kind = g[8], g[9], g[10]
        if m == "J":
            check(g[0] == prio[level], "J: %r: no priority %s" % (l, prio[level]))
        else:
            check(g[0] is None, "%s: %r: a priority prefix outside the journal" % (m, l))
        if pkg == "-":
            check(g[11] == "-" and g[12] == "-" and g[13] is None, "input alarm with numbers: " + l)
        else:
            check(pkg == "crate-A" and g[11] != "-", "package alarm: " + l)
            phys.append(l.split(" ", 3)[3])  # from level= on
    physics[m] = phys
    kinds = {(lv, k) for lv, k in re.findall(r"level=(\w+) package=\S+ kind=(\w+)", "\n".join(alarms))}
    check(any(" reserve_g=" in l for l in alarms), m + ": no alarm line carries the reserve")
    for want in [("critical", "critical"), ("warn", "warn"), ("info", "uplift"), ("warn", "sensor_gap"),
                 ("warn", "reserve_warn")]:
        check(want in kinds, "%s: no %s alarm of kind %s" % (m, want[0], want[1]))
check(physics["J"] == physics["P"] == physics["W"], "the monitors saw different alarms")
print("udpm_alarm_lines.sh: %d package alarms, the same in all three" % len(physics["J"]))
PY

# An error under the journal: priority err.
rc=0
JOURNAL_STREAM=$JS "$SW" monitor --no-such-option 2>>"$T/J.err" || rc=$?
[ "$rc" -eq 2 ] || fail "misuse exited with $rc"
grep -q '^<3>swaywatch: .*no-such-option' "$T/J.err" || fail "no <3> on the error"
echo "ok: alarms on stderr, with priorities in the journal"
