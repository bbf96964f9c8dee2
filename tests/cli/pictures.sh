# SPDX-License-Identifier: GPL-3.0-or-later
# pictures.sh - the state series as a wide CSV (--wide) and the state
# figure (--plot) of replay and simulate: the wide CSV holds the same
# numbers as the long state CSV of the same run (--out, written by another
# path), its ratio is theta over alpha from the scene's own size; the
# figures are valid PNG and SVG files with the series, thresholds and
# events named, and keep a one-sample peak of a long log.
. "$(dirname "$0")/lib.sh"
LOGS=$SRC/sample_logs
BED=$LOGS/crate.ini
FRAME=$LOGS/crate-on-frame.ini
CUSHION=$LOGS/crate-on-cushion.ini

for cmd in replay simulate; do
    run "$SW" $cmd --help
    for opt in --wide --plot 'P.ratio'; do
        grep -q -- "$opt" "$TMP/out" || fail "$cmd --help: $opt not listed"
    done
done

# compare LONG WIDE EVERY: every row of WIDE is the instant of LONG's rows of
# every package, field by field; ratio = theta / atan(width / height), the
# three scenes being 2.0 m high and 0.728 m wide.
compare() {
    python3 - "$1" "$2" "$3" <<'PY' || fail "--wide differs from --out ($1)"
import csv, math, sys
long_rows = list(csv.DictReader(open(sys.argv[1])))
wide = list(csv.DictReader(open(sys.argv[2])))
every = int(sys.argv[3])
names = []
for r in long_rows:
    if r["package"] not in names:
        names.append(r["package"])
    else:
        break
n = len(names)
assert n >= 1 and len(long_rows) % n == 0, (n, len(long_rows))
alpha = math.atan(0.728 / 2.0)
assert len(wide) == len(long_rows) // n, (len(wide), len(long_rows), n)
cols = ["t", "a_g"] + ["%s.%s" % (p, c) for p in names for c in
        ("phase", "theta", "theta_dot", "ratio", "margin", "margin_bound", "uplift_ratio",
         "reserve_g")]
assert list(wide[0].keys()) == cols, list(wide[0].keys())
for i, w in enumerate(wide):
    group = long_rows[i * n:(i + 1) * n]
    assert [g["package"] for g in group] == names, (i, group)
    for g in group:
        p = g["package"]
        assert g["t"] == w["t"] and g["a_g"] == w["a_g"], (i, g, w)
        for c in ("phase", "theta", "theta_dot", "margin", "margin_bound", "uplift_ratio",
                  "reserve_g"):
            assert g[c] == w["%s.%s" % (p, c)], (i, p, c, g[c], w["%s.%s" % (p, c)])
        r = float(w[p + ".ratio"])
        assert math.isclose(r, float(g["theta"]) / alpha, rel_tol=1e-8, abs_tol=1e-15), (i, p, r)
# --every N keeps rows 0, N, 2N, ...: the times step by N sample intervals
if every > 1 and len(wide) > 2:
    dt = float(wide[1]["t"]) - float(wide[0]["t"])
    assert math.isclose(dt, every * 0.001, rel_tol=1e-6), dt
print("compared %d rows of %d packages" % (len(wide), n))
PY
}

# replay: the bed, the frame and the cushion through a braking and a
# pothole (the frame overturns, the cushion too).
for every in 1 7; do
    run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$BED" --scene "$FRAME" --scene "$CUSHION" \
        --out "$TMP/long.csv" --wide "$TMP/wide.csv" --every $every -q
    expect_rc 0 "replay --wide --every $every"
    compare "$TMP/long.csv" "$TMP/wide.csv" $every
done
# simulate, by its own path to the states
run "$SW" simulate --scene "$BED" --scene "$FRAME" --pulse full-sine --amplitude -0.5g \
    --pulse-duration 1.2s --out "$TMP/long.csv" --wide "$TMP/wide.csv" -q
expect_rc 0 "simulate --wide"
compare "$TMP/long.csv" "$TMP/wide.csv" 1
grep -q ',rocking,' "$TMP/wide.csv" || fail "simulate --wide: nothing rocked"

# Packages of the same name are told apart; '-' is standard output (no
# summary there); outputs that clash are refused.
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$BED" --scene "$BED" --wide - -q
expect_rc 0 "--wide -"
head -1 "$TMP/out" | grep -q ',crate-A\.theta,.*,crate-A#2\.theta,' || fail "same names: $(head -1 "$TMP/out")"
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$BED" --wide -
expect_rc 2 "--wide - beside the summary"
expect_err "--wide -: standard output carries the summary" "--wide - beside the summary"
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$BED" --out - --wide - -q
expect_rc 2 "--out - and --wide -"
expect_prefixed_err "--out - and --wide -"
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$BED" --out "$TMP/x.csv" --wide "$TMP/x.csv"
expect_rc 2 "--out and --wide the same file"
expect_err "--out $TMP/x.csv and --wide $TMP/x.csv name the same file" "--out and --wide the same file"
run "$SW" simulate --scene "$BED" --pulse half-sine --amplitude -1g --pulse-duration 0.3s \
    --wide "$TMP/y.svg" --plot "$TMP/y.svg"
expect_rc 2 "--wide and --plot the same file"
expect_err "name the same file" "--wide and --plot the same file"
cp "$BED" "$TMP/scene.svg"
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$TMP/scene.svg" --plot "$TMP/scene.svg"
expect_rc 2 "--plot onto the scene"
expect_err "that is a scene file being read" "--plot onto the scene"
cp "$LOGS/hard-stop-overturn.csv" "$TMP/log.csv"
run "$SW" replay "$TMP/log.csv" --scene "$BED" --wide "$TMP/log.csv"
expect_rc 2 "--wide onto the log"
expect_err "that is the log being read" "--wide onto the log"
cmp -s "$LOGS/hard-stop-overturn.csv" "$TMP/log.csv" || fail "--wide overwrote the log"

if ! command -v gnuplot >/dev/null 2>&1; then
    echo "ok (no gnuplot: figures not checked)"
    exit 0
fi

# png_size FILE: "W H" of a PNG (its IHDR), or nothing if it is not one.
png_size() {
    python3 - "$1" <<'PY'
import struct, sys
b = open(sys.argv[1], "rb").read(33)
if b[:8] == b"\x89PNG\r\n\x1a\n" and b[12:16] == b"IHDR":
    print("%d %d" % struct.unpack(">II", b[16:24]))
PY
}

# svg_has FILE TEXT...: the SVG shows each TEXT (gnuplot writes text as
# <text> elements, entities for a few characters).
svg_has() {
    f=$1
    shift
    python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$f" ||
        fail "$f is not well-formed XML"
    grep -q '<svg' "$f" || fail "$f: no <svg>"
    for want in "$@"; do
        grep -qF -- "$want" "$f" || fail "$f lacks '$want'"
    done
}

run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$BED" --scene "$FRAME" --plot "$TMP/r.png" \
    --events "$TMP/ev.csv" -q
expect_rc 0 "replay --plot png"
[ "$(png_size "$TMP/r.png")" = "1200 960" ] || fail "replay --plot: not a 1200x960 PNG"
grep -q ',crate-A-on-frame,overturn,' "$TMP/ev.csv" || fail "the frame did not overturn"
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$BED" --scene "$FRAME" --plot "$TMP/r.svg" -q
expect_rc 0 "replay --plot svg"
svg_has "$TMP/r.svg" 'swaywatch replay' 'braking-pothole.csv' 'bed acceleration a' \
    'g tan α = 3.57 m/s² (0.364 g): uplift' 'θ/α, crate-A' 'θ/α, crate-A-on-frame' \
    'margin, crate-A-on-frame' 'tipping: |θ| = α' '>uplift<' '>overturn<' 'impact / rest' \
    'time t (s)'
# The same run with and without the figure: the same summary.
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$BED" --scene "$FRAME" --json
cp "$TMP/out" "$TMP/plain.json"
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$BED" --scene "$FRAME" --json --plot "$TMP/r2.svg"
cmp -s "$TMP/out" "$TMP/plain.json" || fail "--plot changed the summary"

# simulate: the pulse in the title, in g and ms
run "$SW" simulate --scene "$BED" --pulse half-sine --amplitude -2g --pulse-duration 300ms \
    --plot "$TMP/s.svg" -q
expect_rc 0 "simulate --plot"
svg_has "$TMP/s.svg" 'half-sine pulse, -2 g, 300 ms' 'θ/α, crate-A' '>overturn<'
run "$SW" simulate --scene "$BED" --pulse half-sine --amplitude -2g --pulse-duration 300ms \
    --plot "$TMP/s.jpg"
expect_rc 2 "--plot .jpg"
expect_err "must end in .png or .svg" "--plot .jpg"
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$BED" --plot "$TMP/no/such/dir.png"
expect_rc 3 "--plot into a missing directory"
expect_prefixed_err "--plot into a missing directory"

# forensics draws the same figure
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$BED" --no-what-if --plot "$TMP/f.svg" -q
expect_rc 0 "forensics --plot"
svg_has "$TMP/f.svg" 'hard-stop-overturn.csv: crate-A' 'θ/α, crate-A' 'margin, crate-A' '>overturn<'

# A log with a lateral column and a package with a depth: the lateral
# plane's tilt in a panel of its own, the lateral acceleration and the
# lateral margin drawn and named, the events named by their plane (the
# crate of depth 0.728 m overturns across the truck on the full shock, the
# one without a depth along it on half of it).
awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 "," 0.5 * $2 "," $2 }' \
    "$LOGS/hard-stop-overturn.csv" >"$TMP/both.csv"
printf '[package]\nname = deep_crate\nheight = 2.0\nwidth = 1.2\ndepth = 0.728\nmass = 1000\n' \
    >"$TMP/deep.ini"
run "$SW" replay "$TMP/both.csv" --scene "$TMP/deep.ini" --scene "$BED" --plot "$TMP/lat.svg" -q
expect_rc 0 "replay --plot with a lateral plane"
svg_has "$TMP/lat.svg" 'tilt along the truck θ / α' 'tilt across the truck θ / α' \
    'across the truck a' 'θ/α across, deep_crate' 'θ/α, deep_crate' 'θ/α, crate-A' \
    'margin across, deep_crate' 'uplift, deep_crate (lateral)' \
    'overturn across the truck, deep_crate' 'overturn along the truck, crate-A' \
    'tip across the truck, deep_crate'
grep -qF 'overturn along the truck, deep_crate' "$TMP/lat.svg" &&
    fail "the lateral overturn named along the truck"
# the one-plane figure keeps its single tilt panel
grep -qF 'tilt along the truck' "$TMP/r.svg" && fail "a one-plane figure names planes"

# A long log (10 minutes at 1 kHz, quiet but for one sample of -40 m/s^2):
# drawn from fixed memory, and the one-sample peak survives the thinning,
# so the acceleration axis reaches -40.
python3 - "$TMP/long.csv" <<'PY'
import sys
with open(sys.argv[1], "w") as f:
    f.write("t,a\n")
    for i in range(600000):
        f.write("%.3f,%s\n" % (i / 1000.0, "-40" if i == 431234 else "0.1"))
PY
run "$SW" replay "$TMP/long.csv" --scene "$BED" --plot "$TMP/long.svg" -q --settle 0
expect_rc 0 "a long log"
svg_has "$TMP/long.svg" '>-40<'
[ "$(wc -c <"$TMP/long.svg")" -lt 2000000 ] || fail "the figure of a long log is $(wc -c <"$TMP/long.svg") bytes"
echo "ok"
