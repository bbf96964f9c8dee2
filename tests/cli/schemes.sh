#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A chosen --scheme or --dt never gives a verdict the default contradicts
# quietly.  On the sample crate on its cushion (omega_c 44.72 rad/s,
# zeta_c 0.05) a 0.05 g braking half-sine of 1 s lifts nothing: explicit
# steps outside their stability region for the cushion's vertical mode
# (Euler beyond 2 zeta_c / omega_c = 2.24 ms, Heun beyond 17.9 ms) are
# refused with a stable dt named, where they used to report it
# overturned.  The default's tilt is the quasi-static one, m h a /
# (K b^2/3 - m g h) = 0.0062 rad, amplified less than twice.  On the bed
# and the frame, Euler at 20-100 ms and Heun at 100 ms near the 1 s
# boundary: every verdict that differs from the default's (a separate
# run without --scheme and --dt) carries scheme_check.agrees = false in
# the JSON and a warning on stderr, and one that agrees neither.
. "$(dirname "$0")/lib.sh"

CUSHION="$SRC/sample_logs/crate-on-cushion.ini"
PULSE="--pulse half-sine --pulse-duration 1s"

run "$SW" simulate --scene "$CUSHION" $PULSE --amplitude -0.05g --json
expect_rc 0 "default"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "upright"'
json_check "$TMP/out" '0.0062 < j["packages"][0]["max_abs_theta"] < 2 * 0.0063'
json_check "$TMP/out" '"scheme_check" not in j["packages"][0] and "dt_requested" not in j["packages"][0]'

for opts in "--scheme euler --dt 0.005 --sample-interval 0.005" "--scheme euler --dt 0.02" \
    "--scheme heun --dt 0.04"; do
    # shellcheck disable=SC2086
    run "$SW" simulate --scene "$CUSHION" $PULSE --amplitude -0.05g $opts --json
    expect_rc 2 "$opts"
    expect_err "stability bound for its cushion's vertical mode" "$opts"
    expect_err "use dt <= " "$opts"
    expect_prefixed_err "$opts"
done
# inside the region: run, checked against the default, and in agreement
run "$SW" simulate --scene "$CUSHION" $PULSE --amplitude -0.05g --scheme euler --dt 0.002 --json
expect_rc 0 "euler 2 ms"
json_check "$TMP/out" 'j["packages"][0]["scheme_check"] == {"scheme": "rk4", "dt": 0.001, "verdict": "upright", "agrees": True}'
[ ! -s "$TMP/err" ] || {
    show
    fail "euler 2 ms: stderr not empty"
}

# The bed and the frame near the boundary of a 1 s half-sine (0.51 g and
# 0.39 g at rest).
differed=0
for sc in crate:0.50,0.52,0.54 crate-on-frame:0.38,0.39,0.40; do
    scene="$SRC/sample_logs/${sc%%:*}.ini"
    for a in $(echo "${sc#*:}" | tr , ' '); do
        run "$SW" simulate --scene "$scene" $PULSE --amplitude "-${a}g" --sample-interval 0.1 --reserve-rate 0 --json
        expect_rc 0 "default $sc $a"
        ref=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["packages"][0]["verdict"])' "$TMP/out")
        for opts in "--scheme euler --dt 0.02" "--scheme euler --dt 0.05" "--scheme euler --dt 0.1" \
            "--scheme heun --dt 0.1"; do
            # shellcheck disable=SC2086
            run "$SW" simulate --scene "$scene" $PULSE --amplitude "-${a}g" --sample-interval 0.1 --reserve-rate 0 $opts \
                --json
            if [ "$RC" -eq 2 ]; then # outside the region for the frame's bearing mode
                expect_err "stability bound for its bearing mode" "$sc $a $opts"
                continue
            fi
            expect_rc 0 "$sc $a $opts"
            got=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["packages"][0]["verdict"])' "$TMP/out")
            json_check "$TMP/out" "j['packages'][0]['scheme_check']['verdict'] == '$ref'"
            if [ "$got" = "$ref" ]; then
                json_check "$TMP/out" 'j["packages"][0]["scheme_check"]["agrees"] is True'
                [ ! -s "$TMP/err" ] || {
                    show
                    fail "$sc $a $opts: a warning where the verdicts agree"
                }
            else
                differed=$((differed + 1))
                json_check "$TMP/out" 'j["packages"][0]["scheme_check"]["agrees"] is False'
                expect_err "warning: " "$sc $a $opts"
                expect_err "says $got, the default (rk4 at dt 1 ms) says $ref" "$sc $a $opts"
            fi
        done
    done
done
[ "$differed" -gt 0 ] || fail "no chosen scheme contradicted the default: the check went untested"

# The human summary says it too.
run "$SW" simulate --scene "$SRC/sample_logs/crate.ini" $PULSE --amplitude -0.52g \
    --sample-interval 0.1 --scheme euler --dt 0.05
expect_rc 0 "summary"
grep -q "default scheme  rk4 at dt 1 ms: overturned -- DIFFERS" "$TMP/out" || {
    show
    fail "the summary does not say the default differs"
}
# The step used is the one reported: on a 1 kHz log a larger --dt is cut
# to the sample interval (steps are aligned to samples), and the JSON and
# the summary say both; a smaller one, or none, is what was asked.
LOG="$SRC/sample_logs/braking-pothole.csv"
CRATE="$SRC/sample_logs/crate.ini"
run "$SW" replay "$LOG" --scene "$CRATE" --dt 0.005 --reserve-rate 0 --json
expect_rc 0 "replay --dt 0.005"
json_check "$TMP/out" 'j["packages"][0]["dt"] == 0.001 and j["packages"][0]["dt_requested"] == 0.005'
run "$SW" replay "$LOG" --scene "$CRATE" --dt 0.005 --reserve-rate 0
grep -q "scheme rk4, dt 1 ms (requested 5 ms)" "$TMP/out" || {
    show
    fail "the summary does not say the step used and the one requested"
}
for opts in "--dt 0.0005" ""; do
    # shellcheck disable=SC2086
    run "$SW" replay "$LOG" --scene "$CRATE" $opts --reserve-rate 0 --json
    expect_rc 0 "replay $opts"
    json_check "$TMP/out" '"dt_requested" not in j["packages"][0]'
done
json_check "$TMP/out" 'j["packages"][0]["dt"] == 0.001'
echo "schemes: ok ($differed contradictions flagged)"
