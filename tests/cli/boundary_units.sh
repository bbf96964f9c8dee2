# SPDX-License-Identifier: GPL-3.0-or-later
# boundary_units.sh - "swaywatch boundary" in physical units: amplitudes in
# g or m/s^2 (--units, --min/--max-amplitude 0.5g), pulses by their
# duration (--pulse-duration 50ms:...).  Every conversion is checked
# against a closed form computed here from the scene's size: R =
# sqrt(h^2 + b^2), p = sqrt(3 g / (4 R)), tan(alpha) = b / h; a half-sine
# of omega_e lasts pi/omega_e, a full-sine 2 pi/omega_e.  The figure
# shows the whole range asked for, the points with no overturn, the side
# each overturns to and the safe islands.
. "$(dirname "$0")/lib.sh"
BLOCK=$SRC/docs/scenes/block-alpha025.ini
CRATE=$SRC/sample_logs/crate.ini

run "$SW" boundary --help
for opt in --units --pulse-duration 5ms:50ms:5ms 'm/s2' duration_ms; do
    grep -q -- "$opt" "$TMP/out" || fail "boundary --help: $opt not listed"
done

# consts FILE: the package's p (rad/s) and g tan(alpha) (m/s^2), g = 9.81
consts() {
    python3 - "$1" <<'PY'
import configparser, math, sys
c = configparser.ConfigParser(inline_comment_prefixes=("#", ";"))
c.read(sys.argv[1])
h = float(c["package"]["height"]) / 2
b = float(c["package"]["width"]) / 2
g = 9.81
print("%.17g %.17g" % (math.sqrt(3 * g / (4 * math.hypot(h, b))), g * b / h))
PY
}
set -- $(consts "$BLOCK")
P=$1 GTAN=$2

# 1. --units g and m/s2: the same curve times g tan(alpha) / 9.80665 and
# g tan(alpha); the duration beside omega_e/p is pi / (omega_e/p p).
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,2,3 --detail "$TMP/d.csv" -q
expect_rc 0 "dimensionless"
cp "$TMP/out" "$TMP/x.csv"
for u in g m/s2; do
    run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,2,3 --units "$u" -q
    expect_rc 0 "--units $u"
    cp "$TMP/out" "$TMP/u.csv"
    python3 - "$TMP/x.csv" "$TMP/u.csv" "$u" "$P" "$GTAN" <<'PY' || fail "--units $u"
import csv, math, sys
x = list(csv.reader(open(sys.argv[1])))
u = list(csv.reader(open(sys.argv[2])))
unit, p, gtan = sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
name = {"g": "block (g)", "m/s2": "block (m/s^2)"}[unit]
assert x[0] == ["omega_ratio", "block"], x[0]
assert u[0] == ["omega_ratio", "duration_ms", name], u[0]
k = gtan / 9.80665 if unit == "g" else gtan
for a, b in zip(x[1:], u[1:]):
    r = float(a[0])
    assert float(b[0]) == r
    assert math.isclose(float(b[1]), math.pi / (r * p) * 1e3, rel_tol=1e-5), (b, r)
    assert math.isclose(float(b[2]), float(a[1]) * k, rel_tol=1e-5), (a, b)
PY
done
# the detail: duration_ms and boundary_g at the end; a positive half-sine
# pushes the top back, and overturns it that way, without an impact
python3 - "$TMP/d.csv" "$P" "$GTAN" <<'PY' || fail "--detail physical columns"
import csv, math, sys
p, gtan = float(sys.argv[2]), float(sys.argv[3])
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 3
for r in rows:
    w = float(r["omega_ratio"])
    assert math.isclose(float(r["duration_ms"]), math.pi / (w * p) * 1e3, rel_tol=1e-5), r
    assert math.isclose(float(r["boundary_g"]), float(r["boundary"]) * gtan / 9.80665, rel_tol=1e-5), r
    assert r["uplift_side"] == "-1" and r["overturn_side"] == "-1" and r["impacts"] == "0", r
PY

# 2. --pulse-duration: the durations of omega_e/p = 1, 2, 3 give the same
# boundary (in g, the default with durations), keyed by the duration.
D=$(python3 -c "import math, sys; p = float(sys.argv[1]); print(','.join('%.12gms' % (math.pi / (r * p) * 1e3) for r in (3, 2, 1)))" "$P")
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --pulse-duration "$D" -q
expect_rc 0 "--pulse-duration $D"
cp "$TMP/out" "$TMP/dur.csv"
python3 - "$TMP/x.csv" "$TMP/dur.csv" "$P" "$GTAN" <<'PY' || fail "--pulse-duration"
import csv, math, sys
x = list(csv.reader(open(sys.argv[1])))[1:]
d = list(csv.reader(open(sys.argv[2])))
p, gtan = float(sys.argv[3]), float(sys.argv[4])
assert d[0] == ["duration_ms", "omega_ratio", "block (g)"], d[0]
d = d[1:]
assert len(d) == 3
for a, b in zip(x, reversed(d)):  # the durations were given shortest first
    r = float(a[0])
    assert math.isclose(float(b[0]), math.pi / (r * p) * 1e3, rel_tol=1e-5), (a, b)
    assert math.isclose(float(b[1]), r, rel_tol=1e-5), (a, b)
    assert math.isclose(float(b[2]), float(a[1]) * gtan / 9.80665, rel_tol=1e-4), (a, b)
PY
# a range: FROM:TO:STEP inclusive, each with its unit; a full-sine lasts 2 pi/omega_e
run "$SW" boundary --scene "$BLOCK" --pulse full-sine --pulse-duration 0.5s:1500ms:250ms --units gtan -q
expect_rc 0 "--pulse-duration range"
python3 - "$TMP/out" "$P" <<'PY' || fail "--pulse-duration range"
import csv, math, sys
d = list(csv.reader(open(sys.argv[1])))
p = float(sys.argv[2])
assert d[0] == ["duration_ms", "omega_ratio", "block"], d[0]
assert [float(r[0]) for r in d[1:]] == [500, 750, 1000, 1250, 1500], d
for r in d[1:]:
    assert math.isclose(float(r[1]), 2 * math.pi / (float(r[0]) * 1e-3 * p), rel_tol=1e-5), r
PY

# 3. --max-amplitude in g is the same scan as in g tan(alpha) converted here.
X=$(python3 -c "import sys; print(repr(0.5 * 9.80665 / float(sys.argv[1])))" "$GTAN")
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,2,3 --max-amplitude 0.5g --detail "$TMP/dg.csv" --out "$TMP/cg.csv"
expect_rc 0 "--max-amplitude 0.5g"
expect_err "1 of 3 points did not overturn up to --max-amplitude 0.5g" "--max-amplitude 0.5g"
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,2,3 --max-amplitude "$X" --detail "$TMP/dx.csv" --out "$TMP/cx.csv" -q
expect_rc 0 "--max-amplitude $X"
cmp -s "$TMP/dg.csv" "$TMP/dx.csv" || fail "--max-amplitude 0.5g differs from $X g tan alpha"
cmp -s "$TMP/cg.csv" "$TMP/cx.csv" || fail "--max-amplitude 0.5g differs from $X g tan alpha"
[ "$(sed -n 4p "$TMP/cg.csv")" = "3," ] || fail "omega_e/p = 3 overturned below 0.5 g: $(sed -n 4p "$TMP/cg.csv")"
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1 --min-amplitude 0.3g --max-amplitude 2.9m/s2
expect_rc 2 "--min-amplitude above --max-amplitude"
expect_err "--min-amplitude 0.3g is not below --max-amplitude 2.9m/s2" "min above max"

# 4. Packages of different sizes: a duration is a different omega_e/p for
# each, so each curve has its own column of the other quantity.
run "$SW" boundary --scene "$BLOCK" --scene "$CRATE" --pulse half-sine --pulse-duration 400ms,800ms -q \
    --max-amplitude 2g
expect_rc 0 "two sizes"
cp "$TMP/out" "$TMP/two.csv"
set -- $(consts "$CRATE")
python3 - "$TMP/two.csv" "$P" "$1" <<'PY' || fail "two sizes, --pulse-duration"
import csv, math, sys
d = list(csv.reader(open(sys.argv[1])))
p = {"block": float(sys.argv[2]), "crate-A": float(sys.argv[3])}
assert p["block"] != p["crate-A"]
assert d[0] == ["duration_ms", "block omega_ratio", "block (g)", "crate-A omega_ratio", "crate-A (g)"], d[0]
for r in d[1:]:
    D = float(r[0]) * 1e-3
    assert math.isclose(float(r[1]), math.pi / (D * p["block"]), rel_tol=1e-5), r
    assert math.isclose(float(r[3]), math.pi / (D * p["crate-A"]), rel_tol=1e-5), r
PY
# swept in two groups, counted as one run
run "$SW" boundary --scene "$BLOCK" --scene "$CRATE" --pulse half-sine --pulse-duration 400ms,800ms \
    --max-amplitude 2g --progress --out "$TMP/two2.csv"
expect_rc 0 "two sizes, --progress"
expect_err "100% (4/4 points)" "two sizes, --progress"
cmp -s "$TMP/two.csv" "$TMP/two2.csv" || fail "two sizes: --progress changed the curves"
run "$SW" boundary --scene "$BLOCK" --scene "$CRATE" --pulse half-sine --omega-ratio 2 --units m/s2 -q
expect_rc 0 "two sizes, --units"
[ "$(head -1 "$TMP/out")" = "omega_ratio,block duration_ms,block (m/s^2),crate-A duration_ms,crate-A (m/s^2)" ] ||
    fail "two sizes, --units: $(head -1 "$TMP/out")"

# 5. Units must be plain: unknown or missing ones are refused with the list.
for bad in "--units furlongs|expected gtan (g tan alpha), g or m/s2" \
    "--pulse-duration 5:50:5|'5' has no unit" "--pulse-duration 5ms:50:5ms|'50' has no unit" \
    "--pulse-duration 5ms:50min:5ms|unknown unit 'min'" \
    "--pulse-duration 5ms:50ms:5ms:1ms|expected FROM:TO:STEP" \
    "--pulse-duration 50ms:5ms:5ms|is after TO" "--pulse-duration 1ms:1s:1us|more than 100000" \
    "--max-amplitude 3ms|unknown unit 'ms'" "--min-amplitude -1g|expected a positive amplitude" \
    "--max-amplitude 20000|out of range" \
    "--max-amplitude 5000g|g tan alpha, out of range: expected 0.001 to 10000" \
    "--pulse-duration 10us,1ms|omega_e/p, out of range: expected 0.001 to 10000"; do
    args=${bad%%|*}
    case $args in --pulse-duration*) ;; *) args="$args --omega-ratio 1" ;; esac
    # shellcheck disable=SC2086
    run "$SW" boundary --scene "$BLOCK" --pulse half-sine $args
    expect_rc 2 "$args"
    expect_prefixed_err "$args"
    expect_err "${bad#*|}" "$args"
done
run "$SW" boundary --scene "$BLOCK" --pulse half-sine
expect_rc 2 "no points"
expect_err "--omega-ratio FROM:TO:STEP or --pulse-duration" "no points"

if ! command -v gnuplot >/dev/null 2>&1; then
    echo "ok (no gnuplot: figures not checked)"
    exit 0
fi

# svg_has FILE TEXT...
svg_has() {
    f=$1
    shift
    python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$f" ||
        fail "$f is not well-formed XML"
    for want in "$@"; do
        grep -qF -- "$want" "$f" || fail "$f lacks '$want'"
    done
}
# 6. The figure: the whole range asked for (omega_e/p up to 12, though
# nothing overturns above 7 below the maximum), the points with no
# overturn marked, the islands, and the duration along the top.  A
# full-sine pulse overturns this block forward (the detail says so), a
# half-sine one back: the legend names the sides there are.
run "$SW" boundary --scene "$BLOCK" --pulse full-sine --omega-ratio 1:12:1 --max-amplitude 5 \
    --islands "$TMP/i.csv" --detail "$TMP/fd.csv" --units g --plot "$TMP/b.svg" -q
expect_rc 0 "--plot, physical"
grep -q ',$' "$TMP/out" || fail "no point without an overturn: $(cat "$TMP/out")"
[ "$(wc -l <"$TMP/i.csv")" -gt 1 ] || fail "no safe islands"
python3 - "$TMP/fd.csv" <<'PY' || fail "full-sine: not all forward"
import csv, sys
sides = {r["overturn_side"] for r in csv.DictReader(open(sys.argv[1])) if r["found"] == "1"}
assert sides == {"1"}, sides
PY
svg_has "$TMP/b.svg" '> 12<' 'peak acceleration a' 'ω' 'pulse duration (ms)' \
    'no overturn up to the maximum' 'overturns forward (top to the front)' \
    'safe islands above the boundary' 'the maximum searched' 'under braking, forward and back swap'
if grep -q 'overturns back' "$TMP/b.svg"; then fail "full-sine: the legend names a side no point has"; fi
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --pulse-duration 100ms:1s:100ms --plot "$TMP/d.svg" -q
expect_rc 0 "--plot, durations"
svg_has "$TMP/d.svg" 'pulse duration (ms)' 'ω' 'overturns back (top to the rear)' 'peak acceleration a'
for absent in 'overturns forward' 'no overturn up to' 'the maximum searched' 'safe islands'; do
    if grep -q "$absent" "$TMP/d.svg"; then fail "half-sine: the legend has '$absent'"; fi
done
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --pulse-duration 100ms:1s:100ms --plot "$TMP/d.png" -q
expect_rc 0 "--plot png"
python3 - "$TMP/d.png" <<'PY' || fail "--plot: not a PNG"
import sys
b = open(sys.argv[1], "rb").read(24)
assert b[:8] == b"\x89PNG\r\n\x1a\n" and b[12:16] == b"IHDR", b
PY
echo "ok"
