#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The lateral plane from lcm-logger files: the sample hard stop as the
# lateral acceleration (accel_t.ay) of a crate of depth 0.728 m, nothing
# along the truck.  Its replay gives the same package (every JSON field:
# the lateral object, the verdict and its plane) and the same --out rows
# as the CSV replay of the same samples with --lat-col; its published
# states carry the plane, two per sample, and its OVERTURNED alarm says
# "sideways" with plane LATERAL.  Without a depth (or with --lat-axis
# none) one state per sample is published, plane 0, exactly as the same
# run makes them with the lateral input ignored; forensics gives the CSV
# log's verdict, plane and safety factor of both axes; --lat-axis equal to
# --axis is refused with a depth, and --flip-lat tips the crate the
# other way.
# usage: lcmlog_lateral.sh SWAYWATCH SOURCE_DIR PYTHONPATH
set -eu
SW=$1 SRC=$2 PYDIR=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "lcmlog_lateral.sh: FAIL: $*" >&2
    exit 1
}
awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 ",0," $2 }' \
    "$SRC/sample_logs/hard-stop-overturn.csv" >"$T/side.csv"
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

# decode.py LOG: per plane, the states' count and thetas; the alarms
cat >"$T/decode.py" <<'PY'
import json, struct, sys
from swaywatch import alarm_t, state_t
out = {"states": {0: [], 1: []}, "alarms": []}
with open(sys.argv[1], "rb") as f:
    while True:
        h = f.read(28)
        if len(h) < 28:
            break
        _s, _n, _ts, cl, dl = struct.unpack(">IqqII", h)
        ch, d = f.read(cl).decode(), f.read(dl)
        if ch == "SWAY_STATE":
            s = state_t.decode(d)
            out["states"][s.plane].append([s.utime, s.theta, s.margin, s.phase, s.reserve_g])
        else:
            a = alarm_t.decode(d)
            text = bytes(b & 0xFF for b in a.text).split(b"\0")[0].decode()
            out["alarms"].append([a.utime, a.kind, a.level, a.plane, text])
json.dump(out, open(sys.argv[2], "w"))
PY

"$SW" replay "$T/side.csv" --scene "$T/deep.ini" --json --out "$T/csv.states" >"$T/csv.json" \
    2>"$T/csv.err" || fail "CSV replay: $(cat "$T/csv.err")"
"$SW" replay "$T/side.lcmlog" --scene "$T/deep.ini" --json --out "$T/lcm.states" \
    --publish "file://$T/pub.lcmlog?mode=w" --speed 0 >"$T/lcm.json" 2>"$T/lcm.err" ||
    fail "lcm-logger replay: $(cat "$T/lcm.err")"
cmp "$T/csv.states" "$T/lcm.states" || fail "the CSV and lcm-logger replays' states differ"
PYTHONPATH=$PYDIR python3 "$T/decode.py" "$T/pub.lcmlog" "$T/pub.json"
python3 - "$T/csv.json" "$T/lcm.json" "$T/pub.json" <<'PY' || fail "the lateral verdicts differ"
import json, sys
a = json.load(open(sys.argv[1]))["packages"][0]
b = json.load(open(sys.argv[2]))["packages"][0]
assert a == b, [(k, a.get(k), b.get(k)) for k in set(a) | set(b) if a.get(k) != b.get(k)]
assert b["overturned"] and b["plane"] == "lateral" and b["lateral"]["overturned"], b
p = json.load(open(sys.argv[3]))
lat, lon = p["states"]["1"], p["states"]["0"]
assert len(lat) == len(lon) == 8001, (len(lat), len(lon))
assert all(s[1] == 0.0 for s in lon)  # nothing along the truck
assert max(s[1] for s in lat) > 1.5  # top to the left: a_y < 0 pushed the bed right
over = [x for x in p["alarms"] if x[1] == 6]
assert len(over) == 1 and over[0][3] == 1 and "overturned sideways" in over[0][4], over
# its time is the verdict's, to the microsecond of utime
t = (over[0][0] - 1700000000000000) / 1e6
assert abs(t - b["lateral"]["overturn_time"]) <= 1e-6, (t, b["lateral"]["overturn_time"])
assert all(x[3] == 0 for x in p["alarms"] if x[4].startswith("accel")), p["alarms"]
PY

# --flip-lat: the other way
"$SW" replay "$T/side.lcmlog" --scene "$T/deep.ini" --flip-lat --publish \
    "file://$T/flip.lcmlog?mode=w" --speed 0 -q >/dev/null 2>&1 || true
PYTHONPATH=$PYDIR python3 "$T/decode.py" "$T/flip.lcmlog" "$T/flip.json"
python3 -c '
import json, sys
lat = json.load(open(sys.argv[1]))["states"]["1"]
assert min(s[1] for s in lat) < -1.5 and max(s[1] for s in lat) < 0.5' "$T/flip.json" ||
    fail "--flip-lat did not tip the crate to the right"

# one plane: no depth, or --lat-axis none; the states as with no lateral input
"$SW" replay "$T/side.lcmlog" --scene "$SRC/sample_logs/crate.ini" --out "$T/one.states" \
    --publish "file://$T/one.lcmlog?mode=w" --speed 0 -q >/dev/null 2>&1 ||
    fail "replay without a depth"
"$SW" replay "$T/side.lcmlog" --scene "$T/deep.ini" --lat-axis none \
    --publish "file://$T/none.lcmlog?mode=w" --speed 0 -q >/dev/null 2>&1 ||
    fail "replay with --lat-axis none"
for x in one none; do
    PYTHONPATH=$PYDIR python3 "$T/decode.py" "$T/$x.lcmlog" "$T/$x.json"
    python3 -c '
import json, sys
p = json.load(open(sys.argv[1]))
assert len(p["states"]["0"]) == 8001 and not p["states"]["1"], sys.argv[1]
assert all(a[3] == 0 for a in p["alarms"]) and all(s[1] == 0.0 for s in p["states"]["0"])' \
        "$T/$x.json" || fail "$x: not one plane"
done
head -1 "$T/one.states" | grep -q '_lat' && fail "lateral columns without a depth"

# forensics reads the lateral acceleration of an lcm-logger file as of a
# CSV log: the same verdict, its plane, and the same safety factor of
# both axes (the lateral plane gives out first)
"$SW" forensics "$T/side.lcmlog" --scene "$T/deep.ini" --no-what-if --json >"$T/for_lcm.json" \
    2>"$T/for.err" || fail "forensics of the lcm-logger file: $(cat "$T/for.err")"
"$SW" forensics "$T/side.csv" --scene "$T/deep.ini" --no-what-if --json >"$T/for_csv.json" \
    2>"$T/for.err" || fail "forensics of the CSV log: $(cat "$T/for.err")"
python3 - "$T/for_lcm.json" "$T/for_csv.json" <<'PY' || fail "forensics: lcm-logger and CSV differ"
import json, sys
a, b = (json.load(open(f))["packages"][0] for f in sys.argv[1:])
assert a["plane"] == b["plane"] == "lateral" and a["verdict"] == b["verdict"] == "overturned", a
for k in ("overturn_time", "max_theta_ratio", "min_margin", "min_reserve_g"):
    assert a[k] == b[k], (k, a[k], b[k])
sa, sb = a["safety_factor"], b["safety_factor"]
assert sa["plane"] == sb["plane"] == "lateral", (sa, sb)
for k in ("bracket", "factor", "factor_safe", "trials"):
    assert sa[k] == sb[k], (k, sa[k], sb[k])
PY
# an axis that is also the longitudinal one: refused, naming --lat-axis
rc=0
"$SW" replay "$T/side.lcmlog" --scene "$T/deep.ini" --axis y >/dev/null 2>"$T/axis.err" || rc=$?
[ "$rc" -eq 2 ] || fail "--axis y with a depth: exit $rc, not 2"
grep -q -- '--lat-axis y is also the longitudinal axis' "$T/axis.err" || fail "$(cat "$T/axis.err")"
# a lateral channel beyond 0.5 g for minutes (gravity on the y axis): no
# verdict, and the refusal names the options of an lcm-logger file, not
# a CSV log's columns
awk 'BEGIN { print "t_s,ax,ay"; for (i = 0; i < 12000; i++) printf "%.3f,%.3f,%.3f\n", i / 100, (i % 5) / 100, 9.7 + (i % 7) / 100 }' \
    >"$T/gravity.csv"
PYTHONPATH=$PYDIR python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/gravity.csv" "$T/gravity.lcmlog" \
    --lat-col 3 --start-utime 1700000000000000 >/dev/null
rc=0
"$SW" replay "$T/gravity.lcmlog" --scene "$T/deep.ini" >/dev/null 2>"$T/gravity.err" || rc=$?
[ "$rc" -eq 2 ] || fail "a lateral channel of gravity: exit $rc, not 2"
grep -q 'the lateral channel looks like gravity' "$T/gravity.err" || fail "$(cat "$T/gravity.err")"
grep -q -- '--lat-axis' "$T/gravity.err" || fail "no --lat-axis in: $(cat "$T/gravity.err")"
! grep -q -- '--lat-col\|--accel-col' "$T/gravity.err" || fail "CSV options named: $(cat "$T/gravity.err")"
[ "$(grep -o -- '--force' "$T/gravity.err" | wc -l)" -eq 1 ] ||
    fail "--force not named once: $(cat "$T/gravity.err")"
echo "ok"
