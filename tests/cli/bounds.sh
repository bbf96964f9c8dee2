#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Every numeric option has bounds, documented in --help and enforced at
# once: values that made the engine hang (--dt 1e-12, --omega 1e-300,
# --settle 1e300, --step 1e-300, --sample-interval 1e-300), fault
# (--rtol/--atol 1e-300), overflow the monitor core (--gap 1e300,
# --state-rate 1e-300) or be accepted and then refuse every sample
# (--max-accel 20000g) are refused with exit 2 and the range, well within
# the timeout.
. "$(dirname "$0")/lib.sh"

SCENE=$SRC/sample_logs/crate.ini
LOG=$SRC/sample_logs/hard-stop-overturn.csv
HAVE_LCM=0
"$SW" --help | grep -q monitor && HAVE_LCM=1

# out CMD OPTION VALUE RANGE: refused, with the range, in seconds
out() {
    cmd=$1 opt=$2 val=$3 range=$4
    case $cmd in
    replay) set -- replay "$LOG" --scene "$SCENE" ;;
    simulate) set -- simulate --scene "$SCENE" --pulse half-sine --amplitude -9 --omega 10 ;;
    forensics) set -- forensics "$LOG" --scene "$SCENE" --no-what-if ;;
    boundary) set -- boundary --scene "$SCENE" --pulse half-sine --omega-ratio 2 ;;
    monitor) set -- monitor --scene "$SCENE" ;;
    esac
    run timeout 10 "$SW" "$@" "$opt" "$val" -q
    expect_rc 2 "$cmd $opt $val"
    expect_err "swaywatch: $opt: out of range: expected $range, got '$val'" "$cmd $opt $val"
    # the same range in --help
    "$SW" "$cmd" --help | tr -s ' \n' '  ' | grep -qF -- "$range)" ||
        fail "$cmd --help: $opt has no range '$range'"
}

out replay --dt 1e-12 "1e-07 to 1"
out replay --dt 1e-300 "1e-07 to 1"
out replay --rtol 1e-300 "1e-14 to 0.01"
out replay --atol 1e-300 "1e-16 to 0.01"
out replay --settle 1e300 "0 to 100000"
out simulate --omega 1e-300 "0.01 to 100000"
out simulate --duration 1e300 "1e-06 to 100000"
out simulate --sample-interval 1e-300 "1e-06 to 10"
out forensics --settle 1e300 "0 to 100000"
out forensics --step 1e-300 "0.0001 to 1"
out forensics --tol 1e-300 "1e-09 to 0.5"
out forensics --max-factor 1e300 "1 to 10000"
out boundary --step 1e-300 "0.0001 to 1"
out boundary --max-amplitude 1e300 "0.001 to 10000"
out boundary --free-periods 1e300 "0.01 to 10000"
run timeout 10 "$SW" boundary --scene "$SCENE" --pulse half-sine --omega-ratio 1e-300 -q
expect_rc 2 "--omega-ratio 1e-300"
expect_err "--omega-ratio: out of range: expected 0.001 to 10000, got '1e-300'" "--omega-ratio"
run timeout 10 "$SW" boundary --scene "$SRC/sample_logs/crate-on-frame.ini" --pulse half-sine \
    --omega-ratio 2 --bearing-ratio 1,1e300 -q
expect_rc 2 "--bearing-ratio 1e300"
expect_err "--bearing-ratio: out of range: expected 0.001 to 1000, got '1e+300'" "--bearing-ratio"
# A long simulate in tiny output steps: refused before it starts.
run timeout 10 "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -9 --omega 10 \
    --duration 1e5 --sample-interval 1e-6 -q
expect_rc 2 "simulate: too many rows"
expect_err "more than 1e+08 steps" "simulate: too many rows"

if [ "$HAVE_LCM" = 1 ]; then
    out monitor --gap 1e300 "0, or 0.0001 to 86400"
    out monitor --state-rate 1e-300 "0, or 0.001 to 1e+06"
    out monitor --max-accel 20000g "0.1 to 100000"
    out monitor --max-skew 1e300 "0, or 0.001 to 1e+09"
    out monitor --status 1e300 "0, or 0.1 to 86400"
    out replay --max-jump 1e300 "0, or 1e-06 to 86400"
    out replay --speed 1e-300 "0, or 0.001 to 1e+06"
fi

# Whole-number options: above the bound is refused, not quietly cut to it
# (a --confirm of 500 used to run with 8); only a thread count is capped.
run timeout 10 "$SW" replay "$LOG" --scene "$SCENE" --confirm 500 -q
expect_rc 2 "--confirm 500"
expect_err "swaywatch: --confirm: out of range: expected 2 to 8, got '500'" "--confirm 500"
run timeout 10 "$SW" forensics "$LOG" --scene "$SCENE" --no-what-if --max-samples 999999999999 -q
expect_rc 2 "--max-samples 999999999999"
expect_err "--max-samples: out of range: expected 1 to 268435456" "--max-samples"
run timeout 60 "$SW" forensics "$LOG" --scene "$SCENE" --no-what-if --threads 100000 -q
expect_rc 0 "--threads 100000 is capped"

# Every physical key of a scene has both bounds: a subnormal or an
# astronomical value (package.mass = 1e-320 was accepted, and the model
# then faulted at every sample) is refused with the file and line, before
# any sample is read; 0 stays allowed where it means "none".
FULL=$TMP/full.ini
cat >"$FULL" <<'INI'
[package]
name = full
height = 2.0
width = 0.728
mass = 1000
[cushion]
omega = 60
zeta = 0.05
cubic = 0
[alarm]
warn_margin = 0.5
INI
FRAME=$SRC/sample_logs/crate-on-frame.ini
for key in package.height package.width package.mass package.g frame.mass frame.stiffness \
    frame.omega frame.damping frame.zeta cushion.stiffness cushion.omega cushion.damping \
    cushion.zeta cushion.cubic alarm.warn_margin alarm.critical_margin alarm.design_pulse \
    alarm.warn_reserve_g alarm.critical_reserve_g; do
    case $key in
    frame.*) sc=$FRAME ;;
    *) sc=$FULL ;;
    esac
    for val in 1e-320 1e-300 1e300; do
        run timeout 10 "$SW" replay "$LOG" --scene "$sc" --set "$key=$val" -q
        expect_rc 2 "--set $key=$val"
        grep -q "^swaywatch: $sc:[0-9]*: ${key}[ =:]\|^swaywatch: $sc:[0-9]*: .*$key" "$TMP/err" ||
            {
                show
                fail "--set $key=$val: not refused with the file, its line and the key"
            }
    done
done
for key in frame.damping frame.zeta cushion.damping cushion.zeta cushion.cubic; do
    case $key in
    frame.*) sc=$FRAME ;;
    *) sc=$FULL ;;
    esac
    run timeout 10 "$SW" replay "$LOG" --scene "$sc" --set "$key=0" -q
    expect_rc 0 "--set $key=0 (none)"
done

# The bounds themselves and the off values are taken.
run "$SW" replay "$LOG" --scene "$SCENE" --dt 1e-4 --rtol 1e-14 --atol 1e-16 --settle 0 -q
expect_rc 0 "values inside the bounds"
if [ "$HAVE_LCM" = 1 ]; then
    run "$SW" replay "$LOG" --scene "$SCENE" --max-accel 100000 --gap 86400 --state-rate 0 -q
    expect_rc 2 "lcm options on a CSV log" # refused as lcm-logger options, not as out of range
    expect_err "is for lcm-logger files" "lcm options on a CSV log"
fi
echo "ok"
