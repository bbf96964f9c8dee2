#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The lateral plane through the command: a log whose lateral column drives
# a crate of depth 0.728 m gives, in the lateral object of the JSON and
# the _lat columns of --out, to the last digit printed, what the
# longitudinal run of the crate of width 0.728 m gives on the same column
# (tests/test_lateral.c shows the engine's planes equal bit for bit); the
# verdict is the worse plane's, named, and --fail-on-overturn sees it; a
# scene with a depth on a log without a lateral column, and a lateral
# column with no depth in any scene, are said on stderr, and the run is
# that of one plane.
. "$(dirname "$0")/lib.sh"

LOG=$SRC/sample_logs/hard-stop-overturn.csv
# the sample drive's acceleration across the truck, nothing along it
awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 ",0," $2 }' "$LOG" >"$TMP/side.csv"
cat >"$TMP/deep.ini" <<'INI'
[package]
name   = crate-A
height = 2.0
width  = 1.2
depth  = 0.728
mass   = 1000
INI

run "$SW" replay "$LOG" --scene "$SRC/sample_logs/crate.ini" --json --out "$TMP/long.csv"
expect_rc 0 "the planar run"
cp "$TMP/out" "$TMP/long.json"
run "$SW" replay "$TMP/side.csv" --scene "$TMP/deep.ini" --json --out "$TMP/side_states.csv"
expect_rc 0 "the lateral run"
expect_err 'lateral: column 3 "ay"' "the lateral column said"
cp "$TMP/out" "$TMP/side.json"
python3 - "$TMP/long.json" "$TMP/side.json" <<'PY' || fail "the lateral plane differs from the planar run"
import json, sys
a = json.load(open(sys.argv[1]))["packages"][0]
p = json.load(open(sys.argv[2]))["packages"][0]
b = p["lateral"]
keys = ["overturned", "verdict", "overturn_time", "tip_time", "uplift_time", "max_abs_theta",
        "max_theta_ratio", "alpha", "min_margin", "min_margin_bound", "max_uplift_ratio",
        "impacts", "uplifts", "rests", "faults", "min_reserve_g", "min_reserve_time",
        "rest_reserve_g", "scheme", "dt", "steps"]
bad = [k for k in keys if a[k] != b[k]]
assert not bad, [(k, a[k], b[k]) for k in bad]
assert a["overturned"] and p["overturned"] and p["plane"] == "lateral", p
assert p["uplifts"] == 0 and p["overturn_time"] is None  # nothing along the truck
assert p["both_planes_rocking"] is False and p["both_planes_from"] is None
PY
# the states: theta and margin of the planar run are theta_lat and margin_lat
python3 - "$TMP/long.csv" "$TMP/side_states.csv" <<'PY' || fail "the lateral states differ"
import csv, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
assert len(a) == len(b) > 8000, (len(a), len(b))
for x, y in zip(a, b):
    assert (x["t"], x["theta"], x["margin"], x["reserve_g"]) == \
        (y["t"], y["theta_lat"], y["margin_lat"], y["reserve_g_lat"]), (x, y)
PY
# the same with the drive that rocks the crate and leaves it standing: its
# smallest reserve, found without a row that shows each state's, too
awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 ",0," $2 }' \
    "$SRC/sample_logs/braking-pothole.csv" >"$TMP/side2.csv"
run "$SW" replay "$SRC/sample_logs/braking-pothole.csv" --scene "$SRC/sample_logs/crate.ini" --json
cp "$TMP/out" "$TMP/long2.json"
run "$SW" replay "$TMP/side2.csv" --scene "$TMP/deep.ini" --json
expect_rc 0 "the lateral run that stands"
python3 - "$TMP/long2.json" "$TMP/out" <<'PY' || fail "the standing lateral plane differs from the planar run"
import json, sys
a = json.load(open(sys.argv[1]))["packages"][0]
b = json.load(open(sys.argv[2]))["packages"][0]["lateral"]
keys = ["overturned", "uplift_time", "max_abs_theta", "min_margin", "impacts", "rests",
        "min_reserve_g", "min_reserve_time", "rest_reserve_g", "steps"]
assert a["min_reserve_g"] is not None and not a["overturned"], a
bad = [k for k in keys if a[k] != b[k]]
assert not bad, [(k, a[k], b[k]) for k in bad]
PY
run "$SW" replay "$TMP/side.csv" --scene "$TMP/deep.ini" --fail-on-overturn
expect_rc 1 "--fail-on-overturn with a lateral overturn"
grep -q "verdict         overturned, decided by the lateral plane (tipped sideways)" "$TMP/out" || {
    show
    fail "the summary does not name the lateral plane"
}

# the drive along and across at once: both planes lifted together, flagged
# from the later of their first lifts
awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 "," $2 "," $2 }' "$LOG" >"$TMP/both.csv"
run "$SW" replay "$TMP/both.csv" --scene "$TMP/deep.ini" --json
expect_rc 0 "both planes"
json_check "$TMP/out" 'j["packages"][0]["both_planes_rocking"] and j["packages"][0]["both_planes_from"] == max(j["packages"][0]["uplift_time"], j["packages"][0]["lateral"]["uplift_time"]) and j["packages"][0]["both_planes_to"] >= j["packages"][0]["both_planes_from"]'
run "$SW" replay "$TMP/both.csv" --scene "$TMP/deep.ini"
grep -q "both planes     lifted at once from" "$TMP/out" || {
    show
    fail "the summary does not say both planes were lifted at once"
}
# forensics marks its verdict the same way, with the replay's span
cp "$TMP/out" "$TMP/both-replay.txt"
run "$SW" replay "$TMP/both.csv" --scene "$TMP/deep.ini" --json
cp "$TMP/out" "$TMP/both-replay.json"
run "$SW" forensics "$TMP/both.csv" --scene "$TMP/deep.ini" --json --no-what-if
expect_rc 0 "forensics, both planes"
python3 - "$TMP/both-replay.json" "$TMP/out" <<'PY' || fail "forensics does not mark both planes rocking as replay does"
import json, sys
r, f = (json.load(open(p))["packages"][0] for p in sys.argv[1:])
assert f["both_planes_rocking"] is True, f
for k in ("both_planes_from", "both_planes_to", "both_planes_time"):
    assert f[k] == r[k], (k, f[k], r[k])
PY

# --flip-lat: the same overturn, tipped to the other side (theta > 0:
# the top toward +y, to the left, as a bed pushed to the right tips it)
run "$SW" replay "$TMP/side.csv" --scene "$TMP/deep.ini" --events - -q
grep -q ",overturn,1.5707963[0-9]*,.*,lateral$" "$TMP/out" || {
    show
    fail "no overturn to +y in the lateral plane"
}
run "$SW" replay "$TMP/side.csv" --scene "$TMP/deep.ini" --flip-lat --events - -q
grep -q ",overturn,-1.5707963[0-9]*,.*,lateral$" "$TMP/out" || {
    show
    fail "--flip-lat: no overturn to -y in the lateral plane"
}

# a depth and no lateral column: one plane, said
run "$SW" replay "$LOG" --scene "$TMP/deep.ini" --json
expect_rc 0 "a depth without a lateral column"
expect_err "no lateral column (--lat-col NAME|N names one)" "a depth without a lateral column"
json_check "$TMP/out" '"lateral" not in j["packages"][0] and "plane" not in j["packages"][0]'

# a lateral column and no depth: not used, said, and the run is the planar one
run "$SW" replay "$TMP/side.csv" --scene "$SRC/sample_logs/crate.ini" --json
expect_rc 0 "a lateral column without a depth"
expect_err 'the lateral column 3 "ay" is not used: no scene gives package.depth' \
    "a lateral column without a depth"
json_check "$TMP/out" 'j["packages"][0]["uplifts"] == 0 and "lateral" not in j["packages"][0]'
run "$SW" replay "$TMP/side.csv" --scene "$SRC/sample_logs/crate.ini" --lat-col ay
expect_rc 0 "--lat-col without a depth"
expect_err "--lat-col ay is not used: no scene gives package.depth" "--lat-col without a depth"

# two lateral columns: refused, naming them and --lat-col
awk -F, 'NR == 1 { print "t_s,X (m/s^2),Y (m/s^2),Lateral (m/s^2)"; next } { print $1 ",0," $2 "," $2 }' \
    "$LOG" >"$TMP/two.csv"
run "$SW" replay "$TMP/two.csv" --scene "$TMP/deep.ini"
expect_rc 2 "two lateral columns"
expect_err "several columns could be the lateral acceleration" "two lateral columns"
expect_err "--lat-col" "two lateral columns"
run "$SW" replay "$TMP/two.csv" --scene "$TMP/deep.ini" --lat-col 4 -q
expect_rc 0 "two lateral columns, one chosen"
# forensics reads the lateral column: the crate overturned across the
# truck by the drive across it is said to, its safety factor is the
# lateral plane's (the planar run's of the crate of width 0.728 m, whose
# factor is the lateral one's to the digit), every what-if case is judged
# across the truck too (none keeps the depth-0.728 m crate upright, so none
# saved it); --fail-on-overturn sees it.
run "$SW" forensics "$LOG" --scene "$SRC/sample_logs/crate.ini" --json --size 2x0.5 \
    --frame-omega 1Hz --cushion-omega 8Hz
expect_rc 0 "forensics, the planar run"
cp "$TMP/out" "$TMP/f_long.json"
run "$SW" forensics "$TMP/side.csv" --scene "$TMP/deep.ini" --json --size 2x0.5 \
    --frame-omega 1Hz --cushion-omega 8Hz --fail-on-overturn
expect_rc 1 "forensics across the truck, --fail-on-overturn"
grep -q 'is not used' "$TMP/err" && fail "forensics: the lateral column not used"
cp "$TMP/out" "$TMP/f_side.json"
python3 - "$TMP/f_long.json" "$TMP/f_side.json" <<'PY' || fail "forensics across the truck"
import json, sys
a = json.load(open(sys.argv[1]))["packages"][0]
p = json.load(open(sys.argv[2]))["packages"][0]
assert p["plane"] == "lateral" and p["overturned"], p
assert p["overturn_time"] == a["overturn_time"], (p["overturn_time"], a["overturn_time"])
sf = p["safety_factor"]
assert sf["plane"] == "lateral", sf
for k in ("bracket", "factor", "factor_safe", "lift_scale", "max_scale"):
    assert sf["planes"]["lateral"][k] == a["safety_factor"][k], k
    assert sf[k] == a["safety_factor"][k], k
# nothing along the truck: that plane never lifts, no scale moves it
assert sf["planes"]["longitudinal"]["lift_scale"] is None, sf["planes"]["longitudinal"]
assert p["saved_by"] == [] and "saved_by_note" not in p, p
for c in p["what_if"]:
    assert c["plane"] == "lateral" and c["overturned"], c
    assert c["lateral"]["overturned"] and c["safety_factor"]["plane"] == "lateral", c
PY
run "$SW" forensics "$TMP/side.csv" --scene "$TMP/deep.ini" --no-what-if -q
expect_rc 0 "forensics across the truck, in words"
grep -q "OVERTURNED across the truck at" "$TMP/out" || fail "forensics: the plane not named"
grep -q "both horizontal axes scaled together: gives out first across the truck" "$TMP/out" ||
    fail "forensics: the plane that gives out first not named"
# batch --csv: the lateral columns hold the lateral object's fields and
# the verdict's plane for a package with a lateral plane, and are empty
# for one without (the crate without a depth on the same log; the same
# crate on a log without a lateral column); the forensics job's hold the
# plane that gives out first and each plane's bracket.
run "$SW" batch "$TMP/side.csv" "$LOG" --scene "$TMP/deep.ini" --scene "$SRC/sample_logs/crate.ini" \
    -o "$TMP/b.jsonl" --csv "$TMP/b.csv" -q
expect_rc 0 "batch with a lateral column"
python3 - "$TMP/b.jsonl" "$TMP/b.csv" <<'PY' || fail "batch --csv: the lateral columns"
import csv, json, sys
recs = [json.loads(l) for l in open(sys.argv[1])]
rows = list(csv.DictReader(open(sys.argv[2])))
assert len(recs) == len(rows) == 4, (len(recs), len(rows))
cols = ["overturned", "verdict", "overturn_time", "tip_time", "uplift_time", "max_abs_theta",
        "max_theta_ratio", "alpha", "min_margin", "impacts", "uplifts", "min_reserve_g",
        "min_reserve_time"]
def cell(v):
    if v is None:
        return ""
    if v is True or v is False:
        return "1" if v else "0"
    if isinstance(v, float):
        return "%.9g" % v
    return str(v)
lateral = 0
for rec, row in zip(recs, rows):
    if "lateral" in rec:
        lateral += 1
        assert row["plane"] == rec["plane"], (row["plane"], rec["plane"])
        assert row["both_planes_rocking"] == cell(rec["both_planes_rocking"])
        for c in cols:
            assert row["lateral_" + c] == cell(rec["lateral"][c]), (c, row["lateral_" + c])
    else:
        assert all(row[k] == "" for k in row if k.startswith("lateral_") or k == "plane"), row
assert lateral == 1, lateral
side = [r for r in rows if r["package"] == "crate-A" and r["lateral_verdict"]][0]
assert side["plane"] == "lateral" and side["lateral_overturned"] == "1", side
PY
run "$SW" batch --job forensics "$TMP/side.csv" --scene "$TMP/deep.ini" --no-what-if \
    -o "$TMP/bf.jsonl" --csv "$TMP/bf.csv" -q
expect_rc 0 "batch --job forensics with a lateral column"
python3 - "$TMP/bf.jsonl" "$TMP/bf.csv" <<'PY' || fail "batch --job forensics --csv: the planes"
import csv, json, sys
rec = json.loads(open(sys.argv[1]).readline())
row = list(csv.DictReader(open(sys.argv[2])))[0]
sf = rec["safety_factor"]
assert row["plane"] == "lateral" and row["factor_plane"] == "lateral", row
assert row["factor"] == "%.9g" % sf["factor"] == row["lateral_factor"], row
assert row["longitudinal_factor"] == "", row  # nothing along the truck: none found
PY
# what-if sizes across the truck, against the closed form of static
# uplift: a bare block of height H and depth d under a lateral step a_y
# (0.3 g from 0.5 s, held 6.5 s) lifts iff a_y > g d / H (physics.md), and
# held this long it then overturns.  The crate of depth 0.4 m (threshold
# 0.2 g) overturns across the truck; as 2x1.2x0.8 (0.4 g) it stays upright
# and is said to have saved it; as 2x1.2x0.5 (0.25 g) and as 2x0.3 (the
# scene's depth kept) it does not.  Each case's safety factor, the step
# scaled, is the threshold over 0.3 g: no scale below it can lift the
# block, and one just above it overturns it within the hold (1 %).
python3 - >"$TMP/step_y.csv" <<'PY'
g = 9.80665
print("t_s,ax,ay")
for i in range(1401):
    t = i * 0.005
    print("%.3f,0,%.6f" % (t, 0.3 * g if t >= 0.5 else 0.0))
PY
awk -F, 'NR == 1 { print "t_s,ax"; next } { print $1 "," $3 }' "$TMP/step_y.csv" >"$TMP/step_x.csv"
cat >"$TMP/tall.ini" <<'INI'
[package]
name   = tall
height = 2.0
width  = 1.2
depth  = 0.4
mass   = 500
INI
run "$SW" forensics "$TMP/step_y.csv" --scene "$TMP/tall.ini" --json --size 2x1.2x0.8 \
    --size 2x1.2x0.5 --size 2x0.3
expect_rc 0 "forensics: what-if sizes across the truck"
cp "$TMP/out" "$TMP/step_y.json"
# the planar identity: the same step along the truck, the block's width
# the depths above, gives the lateral planes' factors to the last digit
sed -e 's/^width .*/width = 0.4/' -e '/^depth/d' "$TMP/tall.ini" >"$TMP/flat.ini"
run "$SW" forensics "$TMP/step_x.csv" --scene "$TMP/flat.ini" --json --size 2x0.8 --size 2x0.5 \
    --no-what-if
expect_rc 0 "forensics: the step along the truck"
cp "$TMP/out" "$TMP/step_x_scene.json"
run "$SW" forensics "$TMP/step_x.csv" --scene "$TMP/flat.ini" --json --size 2x0.8 --size 2x0.5
expect_rc 0 "forensics: the sizes along the truck"
python3 - "$TMP/step_y.json" "$TMP/out" <<'PY' || fail "forensics: what-if sizes across the truck"
import json, sys
p = json.load(open(sys.argv[1]))["packages"][0]
x = json.load(open(sys.argv[2]))["packages"][0]
cases = {c["case"]: c for c in p["what_if"]}
along = {c["case"]: c for c in x["what_if"]}
a_y = 0.3  # g
expect = {  # case: (depth m, saved, the planar case along the truck)
    "as given": (0.4, False, "as given"),
    "size 2x1.2x0.8 m": (0.8, True, "size 2x0.8 m"),
    "size 2x1.2x0.5 m": (0.5, False, "size 2x0.5 m"),
    "size 2x0.3 m": (0.4, False, "as given"),
}
for name, (d, saved, twin) in expect.items():
    c = cases[name]
    thr = (d / 2.0) / a_y  # the scale of the step that reaches g d / H
    assert c["overturned"] == (a_y >= d / 2.0) == (not saved), (name, c)
    if not saved:
        assert c["plane"] == "lateral" and c["lateral"]["overturned"], (name, c)
    sf = c["safety_factor"]
    assert sf["plane"] == "lateral", (name, sf)
    lo, hi = sf["bracket"]
    assert thr <= lo < hi <= 1.01 * thr, (name, thr, sf["bracket"])
    # the lateral plane of the case is the planar case of width d
    lat = sf["planes"]["lateral"]
    assert lat["bracket"] == along[twin]["safety_factor"]["bracket"], (name, lat, along[twin])
    assert c["lateral"]["min_margin"] == along[twin]["min_margin"], (name, c, along[twin])
    assert (name in p["saved_by"]) == saved, (name, p["saved_by"])
    # the case's package says its depth: the one varied, or the scene's kept
    h, w = 2.0, (0.3 if name == "size 2x0.3 m" else 1.2)
    assert c["support"].startswith("%gx%gx%g m, 500 kg" % (h, w, d)), (name, c["support"])
assert p["overturned"] and p["plane"] == "lateral", p
assert "saved_by_note" not in p, p
# one plane: a package without a depth has no plane named in its cases
assert all("plane" not in c and "lateral" not in c for c in x["what_if"]), x["what_if"]
PY
run "$SW" forensics "$TMP/step_y.csv" --scene "$TMP/tall.ini" -q --size 2x1.2x0.8
expect_rc 0 "forensics: what-if sizes across the truck, in words"
grep -q "would have stayed upright: size 2x1.2x0.8 m" "$TMP/out" ||
    fail "forensics: the size across the truck not said to have saved it"
grep -q "what if (the same log, both planes)" "$TMP/out" || fail "forensics: the planes not said"
grep -Eq "^  as given +OVERTURNED across" "$TMP/out" || fail "forensics: the case's plane not named"
grep -q "^tall (2x1.2x0.4 m, 500 kg, on the bed)" "$TMP/out" || fail "forensics: the depth not said"
for bad in 2x1x0 2x1x 2x1xa 2x1x1x1 0x1x1 2x1x-1; do
    run "$SW" forensics "$TMP/step_y.csv" --scene "$TMP/tall.ini" --size "$bad"
    expect_rc 2 "--size $bad"
    expect_err "HEIGHTxWIDTHxDEPTH" "--size $bad"
done
echo "ok lateral"
