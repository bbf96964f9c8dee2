#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The lateral plane live, over UDP multicast with the real LCM tools:
# lcm-logplayer plays the sample hard stop as accel_t.ay (the x axis
# quiet) into a monitor watching a crate of depth 0.728 m; lcm-logger
# records what it publishes.  It must publish a lateral OVERTURNED alarm
# (plane LATERAL, "overturned sideways"), and states of both planes, the
# longitudinal ones still; and the overturn must come at the time the
# independent reference gives: the same values along the truck (accel_t.ax)
# on the crate of width 0.728 m, replayed as a CSV log.
# usage: udpm_lateral.sh SWAYWATCH SOURCE_DIR PYTHONPATH PORT
set -eu
. "$(dirname "$0")/netns.sh"
SW=$1 SRC=$2 PYDIR=$3 PORT=$4
URL="udpm://239.255.76.67:$PORT?ttl=0&recv_buf_size=2097152"
LOG=$SRC/sample_logs/hard-stop-overturn.csv

awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 ",0," $2 }' "$LOG" >"$T/side.csv"
PYTHONPATH=$PYDIR python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/side.csv" "$T/side.lcmlog" \
    --lat-col 3 --start-utime 1700000000000000 >/dev/null
cat >"$T/deep.ini" <<'INI'
[package]
name   = crate-A
height = 2.0
width  = 1.2
depth  = 0.728
mass   = 1000
INI
# the reference: the same values along the truck, the crate of width 0.728 m
"$SW" replay "$LOG" --scene "$SRC/sample_logs/crate.ini" --json >"$T/long.json" 2>/dev/null ||
    fail "the longitudinal reference run"

lcm-logger -q -f -c 'SWAY_.*' --lcm-url="$URL" "$T/rec.lcmlog" &
LOGGER=$!
PIDS="$LOGGER"
# states at 100 Hz a plane: the logger keeps up with every one
"$SW" monitor -l "$URL" --scene "$T/deep.ini" --state-rate 100 --status 1 2>"$T/monitor.err" &
MON=$!
PIDS="$PIDS $MON"
wait_subscribed 4 # the logger and the monitor
lcm-logplayer --lcm-url="$URL" "$T/side.lcmlog"
wait_for "$T/monitor.err" 'accepted 8001, rejected 0'
sleep 0.4 # the logger's last messages
kill -INT "$MON"
wait "$MON" || fail "monitor exited with $?"
kill -INT "$LOGGER"
wait "$LOGGER" || true
grep -q 'overturned sideways' "$T/monitor.err" || fail "no lateral overturn on stderr"

PYTHONPATH=$PYDIR python3 - "$T/rec.lcmlog" "$T/long.json" <<'PY' || fail "what the monitor published"
import json, struct, sys
from swaywatch import alarm_t, state_t
states = {0: [], 1: []}
alarms = []
with open(sys.argv[1], "rb") as f:
    while True:
        h = f.read(28)
        if len(h) < 28:
            break
        _s, _n, _ts, cl, dl = struct.unpack(">IqqII", h)
        ch, d = f.read(cl).decode(), f.read(dl)
        if ch == "SWAY_STATE":
            s = state_t.decode(d)
            states[s.plane].append(s)
        elif ch == "SWAY_ALARM":
            a = alarm_t.decode(d)
            alarms.append((a, bytes(b & 0xFF for b in a.text).split(b"\0")[0].decode()))
# 8 s at 100 Hz, from 0 s to 8 s, in each plane
assert len(states[1]) == len(states[0]) == 801, (len(states[0]), len(states[1]))
assert [s.utime for s in states[0]] == [s.utime for s in states[1]]
assert all(s.plane == state_t.PLANE_LATERAL for s in states[1])
assert all(s.theta == 0.0 and s.phase == state_t.PHASE_STUCK for s in states[0]), "x rocked"
assert states[1][-1].phase == state_t.PHASE_OVERTURNED, states[1][-1].phase
over = [(a, t) for a, t in alarms if a.kind == alarm_t.KIND_OVERTURNED]
assert len(over) == 1, [t for _a, t in alarms]
a, text = over[0]
assert a.plane == alarm_t.PLANE_LATERAL and "overturned sideways" in text, (a.plane, text)
assert a.level == alarm_t.LEVEL_CRITICAL
tip = [a for a, t in alarms if a.kind == alarm_t.KIND_TIP]
assert tip and all(x.plane == alarm_t.PLANE_LATERAL for x in tip)
ref = json.load(open(sys.argv[2]))["packages"][0]
assert ref["overturned"], ref
t = (a.utime - 1700000000000000) / 1e6
assert abs(t - ref["overturn_time"]) <= 1e-6, (t, ref["overturn_time"])
print("ok: overturned sideways at %.6f s, along the truck at %.6f s" % (t, ref["overturn_time"]))
PY
