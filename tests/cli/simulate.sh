# SPDX-License-Identifier: GPL-3.0-or-later
# simulate.sh - pulses through the model: outcomes, outputs, units, options.
. "$(dirname "$0")/lib.sh"
SCENE=$SRC/sample_logs/crate.ini
FRAME=$SRC/sample_logs/crate-on-frame.ini

# Below the uplift threshold g tan(alpha) = 3.57 m/s^2 nothing moves.
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -3 --omega 5 --json --fail-on-overturn
expect_rc 0 "small pulse"
json_check "$TMP/out" 'j["log"] is None and j["pulse"]["shape"] == "half-sine" and j["samples_read"] == 0'
json_check "$TMP/out" 'j["packages"][0]["uplift_time"] is None and j["packages"][0]["max_abs_theta"] == 0 and j["packages"][0]["min_margin"] == 1'

# A hard, short braking pulse overturns the crate.
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -20 --omega 10 --json --fail-on-overturn
expect_rc 1 "big pulse"
cp "$TMP/out" "$TMP/big.json"
json_check "$TMP/big.json" 'j["packages"][0]["overturned"] and j["packages"][0]["overturn_time"] > j["packages"][0]["tip_time"] > j["packages"][0]["uplift_time"] > 0'
grep -Eqi 'nan|infinity' "$TMP/big.json" && fail "NaN or Infinity in the JSON"

# --amplitude-g is the same pulse in g.
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude-g -2.0394324 --omega 10 --json
python3 - "$TMP/big.json" "$TMP/out" <<'PY' || fail "--amplitude-g differs from --amplitude"
import json, math, sys
a, b = (json.load(open(p))["packages"][0] for p in sys.argv[1:3])
assert math.isclose(a["overturn_time"], b["overturn_time"], rel_tol=1e-4), (a, b)
PY

# A pulse as shock standards state it: amplitude in g or m/s^2, duration in
# ms, s or us.  pulse.h: a half-sine of omega lasts pi/omega, a full-sine
# 2 pi/omega.  The same pulse given as omega (computed here) gives the same
# run, and the uplift comes where the closed form puts it: A sin(omega t)
# first reaches g tan(alpha) at t = asin(g tan(alpha) / |A|) / omega
# (crate-A: g = 9.81, tan(alpha) = 0.364 / 1.0).  The JSON has 9 digits.
W=$(python3 -c 'import math; print(repr(math.pi / 0.3))')
for pulse in "-1g 300ms" "-9.80665m/s2 0.3s" "-9.80665 300000us" "-1G 0.3 s"; do
    set -- $pulse
    run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude "$1" --pulse-duration "$2${3:+ $3}" --json
    expect_rc 0 "--amplitude $1 --pulse-duration $2"
    cp "$TMP/out" "$TMP/u.json"
    json_check "$TMP/u.json" 'abs(j["pulse"]["amplitude"] + 9.80665) < 1e-12 and abs(j["pulse"]["duration"] - 0.3) < 1e-12'
    json_check "$TMP/u.json" '__import__("math").isclose(j["pulse"]["omega"], __import__("math").pi / 0.3, rel_tol=1e-8)'
    json_check "$TMP/u.json" 'abs(j["packages"][0]["uplift_time"] - __import__("math").asin(9.81 * 0.364 / 9.80665) / (__import__("math").pi / 0.3)) < 1e-6'
done
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -9.80665 --omega "$W" --json
expect_rc 0 "the same pulse as omega"
python3 - "$TMP/u.json" "$TMP/out" <<'PY' || fail "--pulse-duration differs from --omega"
import json, math, sys
a, b = (json.load(open(p))["packages"][0] for p in sys.argv[1:3])
for k in ("uplift_time", "max_abs_theta", "min_margin", "impacts"):
    assert math.isclose(a[k], b[k], rel_tol=1e-9, abs_tol=1e-12), (k, a[k], b[k])
PY
# A braking half-sine of 10 g, 11 ms (a classic shock-test pulse) and its
# omega pi/0.011 s: the same outcome.
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -10g --pulse-duration 11ms --json
expect_rc 0 "10 g, 11 ms"
cp "$TMP/out" "$TMP/g11.json"
json_check "$TMP/g11.json" '__import__("math").isclose(j["pulse"]["omega"], __import__("math").pi / 0.011, rel_tol=1e-8) and abs(j["pulse"]["amplitude"] + 98.0665) < 1e-9'
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -98.0665 \
    --omega "$(python3 -c 'import math; print(repr(math.pi / 0.011))')" --json
python3 - "$TMP/g11.json" "$TMP/out" <<'PY' || fail "10 g, 11 ms differs from its omega"
import json, math, sys
a, b = (json.load(open(p))["packages"][0] for p in sys.argv[1:3])
assert a["overturned"] == b["overturned"], (a, b)
for k in ("uplift_time", "max_abs_theta", "min_margin"):
    assert math.isclose(a[k], b[k], rel_tol=1e-9, abs_tol=1e-12), (k, a[k], b[k])
PY
# A full sine lasts a whole period: 0.5 s is omega = 2 pi / 0.5.
run "$SW" simulate --scene "$SCENE" --pulse full-sine --amplitude 0.5g --pulse-duration 500ms --json
expect_rc 0 "full-sine duration"
json_check "$TMP/out" '__import__("math").isclose(j["pulse"]["omega"], 4 * __import__("math").pi, rel_tol=1e-8) and abs(j["pulse"]["duration"] - 0.5) < 1e-12'
# Units must be plain: unknown or missing ones are refused with the list.
for bad in "--amplitude 10furlongs --pulse-duration 11ms:unknown unit 'furlongs'" \
    "--amplitude 10ms --pulse-duration 11ms:unknown unit 'ms'" \
    "--amplitude 10g --pulse-duration 11min:unknown unit 'min'" \
    "--amplitude 10g --pulse-duration 11g:unknown unit 'g'" \
    "--amplitude 10g --pulse-duration 11:'11' has no unit" \
    "--amplitude 10g --pulse-duration -11ms:expected a positive time" \
    "--amplitude 0g --pulse-duration 11ms:expected a non-zero acceleration" \
    "--amplitude 10g --pulse-duration 11ms --omega 3:give one" \
    "--amplitude 10g --pulse-duration 10us:out of range: a half-sine of omega 0.01 to 100000 rad/s" \
    "--amplitude 10g --pulse-duration 400s:lasts 3.14159e-05 to 314.159 s, got 400 s" \
    "--amplitude 10g:--omega W (rad/s) or --pulse-duration D"; do
    args=${bad%%:*}
    # shellcheck disable=SC2086
    run "$SW" simulate --scene "$SCENE" --pulse half-sine $args
    expect_rc 2 "$args"
    expect_prefixed_err "$args"
    expect_err "${bad#*:}" "$args"
done
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude 10gs --pulse-duration 11ms -q
expect_rc 0 "Gs is g, as in CSV headers"
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude 10furlongs --pulse-duration 11ms
expect_err "expected g or m/s2" "the units accepted"
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude 10g --pulse-duration 11h
expect_err "expected ms, s or us" "the units accepted"

# A medium pulse: it rocks, comes back, and the outputs are complete.
run "$SW" simulate --scene "$SCENE" --scene "$FRAME" --pulse half-sine --amplitude -6 --omega 6.2832 \
    --out "$TMP/state.csv" --events "$TMP/events.csv" --sample-interval 0.01 --duration 5 --json
expect_rc 0 "medium pulse"
cp "$TMP/out" "$TMP/medium.json"
json_check "$TMP/medium.json" 'j["packages"][0]["uplift_time"] is not None and not j["packages"][0]["overturned"]'
json_check "$TMP/medium.json" 'all(set(["name", "model", "overturned", "overturn_time", "tip_time", "max_abs_theta", "max_theta_ratio", "min_margin", "uplift_time", "impacts", "samples_read", "samples_rejected", "scheme", "dt"]) <= set(p) for p in j["packages"])'
[ "$(head -1 "$TMP/state.csv")" = "t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,uplift_ratio,a_g,reserve_g" ] ||
    fail "--out header"
tail -n +2 "$TMP/state.csv" | grep -Eqi 'nan|inf' && fail "--out holds nan or inf"
# One row per package at t = 0, 0.01, ..., 5 (or until both are at rest).
python3 - "$TMP/state.csv" <<'PY' || fail "--out rows not on the sample grid"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
ts = sorted({float(r["t"]) for r in rows if r["package"] == "crate-A"})
assert ts[0] == 0.0, ts[:3]
assert all(math.isclose(b - a, 0.01, abs_tol=1e-9) for a, b in zip(ts, ts[1:])), "grid"
assert len(ts) > 100, len(ts)
assert any(r["phase"] == "rocking" for r in rows)
PY
grep -q ',crate-A,uplift,' "$TMP/events.csv" || fail "--events: no uplift"

# The pulse is exact input: the sample interval does not change the physics.
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -6 --omega 6.2832 \
    --sample-interval 0.001 --duration 5 --json
python3 - "$TMP/medium.json" "$TMP/out" <<'PY' || fail "--sample-interval changed the result"
import json, math, sys
a, b = (json.load(open(p))["packages"][0] for p in sys.argv[1:3])
for k in ("uplift_time", "max_abs_theta", "min_margin"):
    assert math.isclose(a[k], b[k], rel_tol=1e-6, abs_tol=1e-9), (k, a[k], b[k])
PY

# --verbose: derived quantities on stderr, stdout untouched.
run "$SW" simulate --scene "$FRAME" --pulse full-sine --amplitude 4 --omega 3 --verbose --json
expect_rc 0 "--verbose"
python3 -m json.tool "$TMP/out" >/dev/null || fail "--verbose spoilt the JSON"
for want in 'alpha' '  p ' 'eta' 'gamma' 'omega_b' 'zeta_b' 'r_frame' '  dt '; do
    expect_err "$want" "--verbose lists $want"
done

# Every scheme named in the table runs and is echoed in the summary.
run "$SW" simulate --help
# (the --scheme row's help may go on over several lines)
schemes=$(awk '/--scheme NAME/ {on = 1} on {s = s " " $0} on && /\(default/ {exit} END {print s}' \
    "$TMP/out" | sed -n 's/.*time stepper: *\(.*\) (default.*/\1/p' | tr -d ,)
[ -n "$schemes" ] || fail "no schemes listed in --help"
for s in $schemes; do
    run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -6 --omega 6.2832 --duration 3 --scheme "$s" --json
    expect_rc 0 "--scheme $s"
    json_check "$TMP/out" "j['packages'][0]['scheme'] == '$s'"
done
echo "ok"

# --verbose on a cushion scene prints the static deflection and the natural
# frequencies: K = 1000 kg * (200 rad/s)^2 = 4e7 N/m, b = 0.364 m, h = 1 m,
# R^2 = h^2 + b^2: z = m g / K = 2.4525e-4 m, omega_z = 200 rad/s,
# omega_r = sqrt((K b^2/3 - m g h) / (m R^2/3 + m h^2)) = 35.712 rad/s.
printf '[package]\nname = c1\nheight = 2.0\nwidth = 0.728\nmass = 1000\n[cushion]\nomega = 200\nzeta = 0.1\n' > "$TMP/cushion.ini"
run "$SW" simulate --scene "$TMP/cushion.ini" --pulse half-sine --amplitude -5 --omega 10 --verbose
expect_rc 0 "cushion --verbose"
python3 - "$TMP/err" <<'PY' || fail "cushion --verbose quantities"
import re, sys, math
t = open(sys.argv[1]).read()
def val(name):
    return float(re.search(r"^\s*%s\s+(\S+)" % re.escape(name), t, re.M).group(1))
K, b, h, m, g = 4e7, 0.364, 1.0, 1000.0, 9.81
assert math.isclose(val("z_static"), m * g / K, rel_tol=1e-4)
assert math.isclose(val("omega_z"), 200.0, rel_tol=1e-4)
wr = math.sqrt((K * b * b / 3 - m * g * h) / (m * (h * h + b * b) / 3 + m * h * h))
assert math.isclose(val("omega_r"), wr, rel_tol=1e-4), (val("omega_r"), wr)
PY

# --accuracy picks the setting from the measured table (the errors it
# promises are checked against rk8pd in tests/test_accuracy.c).
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -6 --omega 6.2832 --accuracy 1e-6 --json
expect_rc 0 "--accuracy 1e-6"
json_check "$TMP/out" 'j["packages"][0]["scheme"] == "rk4" and abs(j["packages"][0]["dt"] - 1e-3) < 1e-12'
run "$SW" simulate --scene "$SCENE" --scene "$FRAME" --pulse half-sine --amplitude -6 --omega 6.2832 --accuracy 5e-14 --json
expect_rc 0 "--accuracy 5e-14"
json_check "$TMP/out" 'all(p["scheme"] == "rkck" for p in j["packages"])'
# ... and simulate delivers it: max|theta| within 1e-9 rad of rk8pd at
# rtol 1e-13 (the JSON's 9 digits resolve about 1e-10 rad here;
# tests/test_accuracy.c checks 1e-10 to 1e-13 at full precision).  A step
# across the pulse's end missed it by 1e-7 rad.  Rows of 0.1 s: steps of
# an adaptive row stay within the 1 ms it was measured at.
for sc in "$SCENE:-7.1417:7.8882" "$FRAME:-6.0704:7.8882"; do
    IFS=: read -r scene amp omega <<EOF2
$sc
EOF2
    for rows in 0.001 0.1; do
        run "$SW" simulate --scene "$scene" --pulse half-sine --amplitude "$amp" --omega "$omega" \
            --sample-interval "$rows" --reserve-rate 0 --scheme rk8pd --rtol 1e-13 --atol 1e-15 --json
        expect_rc 0 "rk8pd reference"
        cp "$TMP/out" "$TMP/ref.json"
        for acc in 1e-9 1e-12; do
            run "$SW" simulate --scene "$scene" --pulse half-sine --amplitude "$amp" --omega "$omega" \
                --sample-interval "$rows" --reserve-rate 0 --accuracy "$acc" --json
            expect_rc 0 "--accuracy $acc"
            python3 - "$TMP/out" "$TMP/ref.json" <<'PY' || fail "$scene, rows of $rows s: --accuracy $acc not met"
import json, sys
a, r = (json.load(open(f))["packages"][0]["max_abs_theta"] for f in sys.argv[1:3])
print("max|theta| %.9g, reference %.9g, error %.2g" % (a, r, abs(a - r)), file=sys.stderr)
sys.exit(0 if abs(a - r) <= 1e-9 else 1)
PY
        done
    done
done
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -6 --omega 6.2832 --accuracy 1e-20
expect_rc 2 "--accuracy beyond the table"
expect_err "tighter than any measured setting"
expect_prefixed_err "--accuracy beyond the table"
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -6 --omega 6.2832 --accuracy 1e-6 --scheme heun
expect_rc 2 "--accuracy with --scheme"

# A scene without package.name is named after its file.
printf '[package]\nheight = 2.0\nwidth = 0.728\nmass = 1000\n' > "$TMP/unnamed-crate.ini"
run "$SW" simulate --scene "$TMP/unnamed-crate.ini" --pulse half-sine --amplitude -3 --omega 5 --json
expect_rc 0 "scene without a name"
json_check "$TMP/out" 'j["packages"][0]["name"] == "unnamed-crate"'
