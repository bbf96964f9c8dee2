# SPDX-License-Identifier: GPL-3.0-or-later
# boundary.sh - "swaywatch boundary": usage, the CSV, threads = one thread,
# the bare block against the reference tables, a boundary point re-run with
# simulate and the rk8pd reference scheme just below and above it.
. "$(dirname "$0")/lib.sh"
BLOCK=$SRC/docs/scenes/block-alpha025.ini
BARE=$SRC/docs/scenes/paper-bare.ini
FRAME=$SRC/docs/scenes/paper-frame.ini

run "$SW" boundary --help
expect_rc 0 "boundary --help"
[ ! -s "$TMP/err" ] || fail "boundary --help wrote to stderr"
grep -q '^usage: swaywatch boundary' "$TMP/out" || fail "boundary --help: no usage line"
for opt in --scene --set --pulse --omega-ratio --vary --bearing-ratio --threads --out --plot \
    --progress --step --tol --max-amplitude --islands --detail 'Exit codes: 0 ok'; do
    grep -q -- "$opt" "$TMP/out" || fail "boundary --help: $opt not listed"
done

# misuse: exit 2, prefixed messages
run "$SW" boundary --scene "$BLOCK" --omega-ratio 1:2:1
expect_rc 2 "no --pulse"
expect_prefixed_err "no --pulse"
expect_err "--pulse" "no --pulse"
for bad in "2:1:0.5" "1:2:0" "1:2" "x" "1,,2" "0,1"; do
    run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio "$bad"
    expect_rc 2 "--omega-ratio $bad"
    expect_prefixed_err "--omega-ratio $bad"
done
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1 --bearing-ratio 1/2
expect_rc 2 "--bearing-ratio without a frame"
expect_err "no scene has a [frame]" "--bearing-ratio without a frame"
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1 --vary package.nonesuch=1,2
expect_rc 2 "--vary of an unknown key"
expect_prefixed_err "--vary of an unknown key"
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1 --plot "$TMP/x.jpg"
expect_rc 2 "--plot with another extension"
run "$SW" boundary --scene "$TMP/none.ini" --pulse half-sine --omega-ratio 1
expect_rc 3 "missing scene file"

# The bare block of the reference tables (alpha = 0.25 rad): rocking-anchors
# section 2.2 gives 1.321, 1.801, 2.297 at omega/p = 1, 2, 3 (rounded to
# 3 decimals); the --detail bracket [safe_below, boundary] must hold them
# within that rounding.
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1:3:1 --detail "$TMP/d.csv"
expect_rc 0 "bare block"
[ "$(head -1 "$TMP/out")" = "omega_ratio,block" ] || { show; fail "CSV header"; }
[ "$(wc -l <"$TMP/out")" -eq 4 ] || { show; fail "CSV rows"; }
python3 - "$TMP/d.csv" <<'PY' || fail "bare block against the reference tables"
import csv, sys
ref = {1.0: 1.321, 2.0: 1.801, 3.0: 2.297}
for r in csv.DictReader(open(sys.argv[1])):
    w, lo, hi = float(r["omega_ratio"]), float(r["safe_below"]), float(r["boundary"])
    assert lo - 6e-4 <= ref[w] <= hi + 6e-4, (w, lo, hi, ref[w])
    assert r["impacts"] == "0", r  # the half-sine overturns without an impact
PY

# The same sweep on one thread and on two gives the same bytes, for the
# curves, the detail and the islands.
for n in 1 2; do
    run "$SW" boundary --scene "$BARE" --scene "$FRAME" --bearing-ratio 1,1/3 --pulse full-sine \
        --omega-ratio 1:7:1.5 --max-amplitude 12 --threads $n --out "$TMP/c$n.csv" \
        --detail "$TMP/d$n.csv" --islands "$TMP/i$n.csv" --no-progress
    expect_rc 0 "--threads $n"
done
cmp "$TMP/c1.csv" "$TMP/c2.csv" || fail "curves differ between 1 and 2 threads"
cmp "$TMP/d1.csv" "$TMP/d2.csv" || fail "detail differs between 1 and 2 threads"
cmp "$TMP/i1.csv" "$TMP/i2.csv" || fail "islands differ between 1 and 2 threads"
[ "$(head -1 "$TMP/c1.csv")" = "omega_ratio,bed,frame wb/we=1,frame wb/we=1/3" ] ||
    fail "curve names: $(head -1 "$TMP/c1.csv")"

# It says on stderr what it wrote: each file, its curves, points, rows.
expect_err "swaywatch: boundary: wrote $TMP/c2.csv: 3 curves at 5 points" "what it wrote"
expect_err "swaywatch: boundary: wrote $TMP/d2.csv: 15 rows, one per curve and point" \
    "what it wrote"
n=$(($(wc -l <"$TMP/i2.csv") - 1))
expect_err "swaywatch: boundary: wrote $TMP/i2.csv: $n safe island" "what it wrote"
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,2 --no-progress
expect_err "swaywatch: boundary: wrote standard output: 1 curve at 2 points" "curves on stdout"
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,2 -q --out "$TMP/q.csv"
[ ! -s "$TMP/err" ] || { show; fail "-q: boundary wrote to stderr"; }

# A point with no overturn below --max-amplitude is an empty field.
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1,8 --max-amplitude 3
expect_rc 0 "empty field"
sed -n 3p "$TMP/out" | grep -qx '8,' || { show; fail "no empty field at omega/p = 8"; }
expect_err "did not overturn up to --max-amplitude 3" "empty field"

# --vary: one curve per value, the scene file untouched otherwise.
run "$SW" boundary --scene "$BARE" --scene "$FRAME" --bearing-ratio 1/2 --vary frame.zeta=0.05,0.4 \
    --pulse half-sine --omega-ratio 2
expect_rc 0 "--vary"
[ "$(head -1 "$TMP/out")" = "omega_ratio,bed,frame frame.zeta=0.05 wb/we=1/2,frame frame.zeta=0.4 wb/we=1/2" ] ||
    { show; fail "--vary curve names"; }

# A boundary point re-run by simulate with the rk8pd reference: 1 % below
# it the package stays up, 1 % above it overturns (after one impact: the
# full-sine's first mode).  Frame points are re-run in tests/test_sweep.c.
run "$SW" boundary --scene "$BARE" --pulse full-sine --omega-ratio 2
expect_rc 0 "bare point"
x=$(sed -n 2p "$TMP/out" | cut -d, -f2)
eval "$(python3 - "$x" <<'PY'
import math, sys
x = float(sys.argv[1])
a = math.radians(20.0)
p = math.sqrt(3 * 9.81 / 4)  # R = 1 m
print("W=%.17g LO=%.17g HI=%.17g" % (2 * p, 0.99 * x * 9.81 * math.tan(a), 1.01 * x * 9.81 * math.tan(a)))
PY
)"
for amp in $LO $HI; do
    run "$SW" simulate --scene "$BARE" --pulse full-sine --amplitude $amp --omega $W --scheme rk8pd \
        --duration 60 --json
    expect_rc 0 "simulate at $amp"
    cp "$TMP/out" "$TMP/sim-$amp.json"
done
json_check "$TMP/sim-$LO.json" 'not j["packages"][0]["overturned"]'
json_check "$TMP/sim-$HI.json" 'j["packages"][0]["overturned"] and j["packages"][0]["impacts"] == 1'

# --plot: a PNG and an SVG (gnuplot as a subprocess)
if command -v gnuplot >/dev/null 2>&1; then
    run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1:3:1 --plot "$TMP/b.png" \
        --out "$TMP/b.csv"
    expect_rc 0 "--plot png"
    head -c 8 "$TMP/b.png" | od -An -tx1 | grep -q '89 50 4e 47' || fail "--plot: not a PNG"
    run "$SW" boundary --scene "$BLOCK" --pulse full-sine --omega-ratio 1:3:1 --plot "$TMP/b.svg" \
        --out "$TMP/b.csv" --islands "$TMP/bi.csv" --max-amplitude 4
    expect_rc 0 "--plot svg"
    grep -q '<svg' "$TMP/b.svg" || fail "--plot: not an SVG"
    run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1 --plot "$TMP/no/such/dir.png"
    expect_rc 3 "--plot into a missing directory"
    expect_prefixed_err "--plot into a missing directory"
fi

# --progress: a percentage on stderr even when it is not a terminal
run "$SW" boundary --scene "$BLOCK" --pulse half-sine --omega-ratio 1:2:1 --progress
expect_rc 0 "--progress"
expect_err "100% (2/2 points)" "--progress"

# --plane lateral: the curve of the lateral plane is the planar one over
# the depth on the lateral support values, so a crate of depth 0.728 m
# gives, to the last digit, the curves and the detail of the crate of
# width 0.728 m: bare, and on a frame whose lateral bearings (omega 3)
# are softer than those along (omega 5.59); --vary package.depth varies
# the size it rocks over.  Without a depth it is refused with the reason.
printf '[package]\nname = c\nheight = 2.0\nwidth = 1.3\ndepth = 0.728\nmass = 1000\n' >"$TMP/bd.ini"
printf '[package]\nname = c\nheight = 2.0\nwidth = 0.728\nmass = 1000\n' >"$TMP/bw.ini"
cp "$TMP/bd.ini" "$TMP/fd.ini"
printf '[frame]\nmass = 250\nomega = 5.59\nzeta = 0.1\nlateral_omega = 3\n' >>"$TMP/fd.ini"
cp "$TMP/bw.ini" "$TMP/fw.ini"
printf '[frame]\nmass = 250\nomega = 3\nzeta = 0.1\n' >>"$TMP/fw.ini"
for kind in b f; do
    for pulse in half-sine full-sine; do
        run "$SW" boundary --scene "$TMP/${kind}d.ini" --pulse $pulse --omega-ratio 0.5:6:0.5 \
            --plane lateral -o "$TMP/lat.csv" --detail "$TMP/lat_d.csv" -q
        expect_rc 0 "--plane lateral ($kind, $pulse)"
        run "$SW" boundary --scene "$TMP/${kind}w.ini" --pulse $pulse --omega-ratio 0.5:6:0.5 \
            -o "$TMP/long.csv" --detail "$TMP/long_d.csv" -q
        expect_rc 0 "the planar run ($kind, $pulse)"
        cmp -s "$TMP/lat.csv" "$TMP/long.csv" || fail "--plane lateral ($kind, $pulse): curves differ"
        cmp -s "$TMP/lat_d.csv" "$TMP/long_d.csv" || fail "--plane lateral ($kind, $pulse): detail differs"
    done
done
# the lateral plane of the 1.3 m wide crate is not its longitudinal one
run "$SW" boundary --scene "$TMP/bd.ini" --pulse half-sine --omega-ratio 0.5:6:0.5 -o "$TMP/along.csv" -q
cmp -s "$TMP/along.csv" "$TMP/lat.csv" && fail "--plane lateral: the curve along the truck"
run "$SW" boundary --scene "$TMP/bd.ini" --pulse half-sine --omega-ratio 1:3:1 --plane lateral \
    --vary package.depth=0.728,0.6 -o "$TMP/lat.csv" -q
expect_rc 0 "--plane lateral --vary package.depth"
run "$SW" boundary --scene "$TMP/bw.ini" --pulse half-sine --omega-ratio 1:3:1 \
    --vary package.width=0.728,0.6 -o "$TMP/long.csv" -q
cmp -s "$TMP/lat.csv" "$TMP/long.csv" || fail "--plane lateral --vary package.depth"
run "$SW" boundary --scene "$TMP/bw.ini" --pulse half-sine --omega-ratio 1 --plane lateral
expect_rc 2 "--plane lateral without a depth"
expect_err "--plane lateral: $TMP/bw.ini gives no [package] depth" "--plane lateral without a depth"
run "$SW" boundary --scene "$TMP/bd.ini" --pulse half-sine --omega-ratio 1 --plane lateral \
    --vary package.width=1,2
expect_rc 2 "--plane lateral --vary package.width"
expect_err "vary package.depth" "--plane lateral --vary package.width"
run "$SW" boundary --scene "$TMP/bd.ini" --pulse half-sine --omega-ratio 1 --plane sideways
expect_rc 2 "--plane sideways"
expect_err "expected longitudinal or lateral" "--plane sideways"

echo "ok"
