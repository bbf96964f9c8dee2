#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# What a scene costs is estimated from the scene, never timed:
#  - scenes inside every documented limit that the engine runs slower than
#    real time (a frame of 1e7 kg on bearings of 1e6 rad/s with no damping,
#    alone or under a stiff cushion) are warned about, with the steps per
#    second the estimate counts: twice the fastest mode, omega_max =
#    omega_b / sqrt(1 - 3 gamma / 4) (physics.md), for rk4's sub-steps;
#  - the stock scenes are not, also when every CPU-time measurement comes
#    out a million times too long (an LD_PRELOAD clock, as on a loaded
#    machine: a timer would call them too stiff);
#  - the reserve with 8 design pulses is warned about (its cost grows with
#    the pulses), with one it is not;
#  - the monitor warns at start and after a reload that brings one in.
. "$(dirname "$0")/lib.sh"

cat >"$TMP/frame.ini" <<'INI'
[package]
name = stiff-frame
height = 2.0
width = 0.728
mass = 1000
[frame]
mass = 1e7
omega = 1e6
zeta = 0
INI
cp "$TMP/frame.ini" "$TMP/both.ini"
cat >>"$TMP/both.ini" <<'INI'
[cushion]
omega = 1e5
zeta = 0.05
cubic = 1e20
INI
sed -i 's/stiff-frame/stiff-both/' "$TMP/both.ini"
printf 't,a\n0,0\n0.001,-1\n0.002,0\n' >"$TMP/short.csv"
WARN='warning: scene %s needs about [0-9.e+]* steps per second of input'

# warned NAME WHAT: stderr has the warning for scene NAME, with a factor < 10
warned() {
    # shellcheck disable=SC2059
    grep -q "^swaywatch: $(printf "$WARN" "$1")" "$TMP/err" || {
        show
        fail "$2: no warning naming the steps"
    }
    f=$(sed -n "s/.*scene $1 needs .*estimated at only \([0-9.e+-]*\) times.*/\1/p" "$TMP/err" |
        head -1)
    python3 -c "import sys; sys.exit(0 if float('$f') < 10 else 1)" ||
        fail "$2: factor $f is not below 10"
}

run "$SW" replay "$TMP/short.csv" --scene "$TMP/both.ini" --settle 0 -q
expect_rc 0 "replay, frame and cushion"
warned stiff-both "replay, frame and cushion"
run "$SW" simulate --scene "$TMP/frame.ini" --pulse half-sine --amplitude -9 --omega 10 \
    --duration 0.01 -q
expect_rc 0 "simulate, frame"
warned stiff-frame "simulate, frame"
# the steps counted: rk4 sub-steps to omega_max h = 0.5
steps=$(sed -n 's/.*scene stiff-frame needs about \([0-9.e+]*\) steps.*(rk4, step.*/\1/p' \
    "$TMP/err")
python3 - "$steps" <<'PY' || fail "stiff-frame: $steps steps per second"
import math, sys
gamma = 1000 / (1000 + 1e7)
w_max = 1e6 / math.sqrt(1 - 0.75 * gamma)
got = float(sys.argv[1])
sys.exit(0 if abs(got - 2 * w_max) <= 5e-3 * 2 * w_max else 1)
PY

# the stock scenes: no warning, whatever a clock would say
STOCK="--scene $SRC/sample_logs/crate.ini --scene $SRC/sample_logs/crate-on-frame.ini
       --scene $SRC/sample_logs/crate-on-cushion.ini"
# shellcheck disable=SC2086
run "$SW" replay "$TMP/short.csv" $STOCK --settle 0 -q
expect_rc 0 "ordinary scenes"
! grep -q 'warning' "$TMP/err" || fail "ordinary scenes: warned"
if [ -n "${SW_FASTCLOCK:-}" ] && ! ldd "$SW" 2>/dev/null | grep -q 'libasan'; then
    # shellcheck disable=SC2086
    LD_PRELOAD=$SW_FASTCLOCK run "$SW" replay "$TMP/short.csv" $STOCK --settle 0 -q
    expect_rc 0 "ordinary scenes, CPU clock a million times fast"
    ! grep -q 'warning' "$TMP/err" || {
        show
        fail "ordinary scenes, CPU clock a million times fast: warned"
    }
fi

# the reserve: eight design pulses of 1 to 8 s on the stock crate cost
# about a hundred times one (measured: 30 ms an evaluation while rocking)
run "$SW" replay "$TMP/short.csv" --scene "$SRC/sample_logs/crate.ini" --settle 0 -q \
    --set alarm.design_pulse=1,2,3,4,5,6,7,8
expect_rc 0 "8 design pulses"
expect_err "warning: the reserve of 1 package, evaluated 10 times per second of input, may take up to" \
    "8 design pulses"
expect_err "(crate-A: 8 design pulses, up to" "8 design pulses"
run "$SW" replay "$TMP/short.csv" --scene "$SRC/sample_logs/crate.ini" --settle 0 -q \
    --set alarm.design_pulse=1,2,3,4,5,6,7,8 --reserve-rate 1
expect_rc 0 "8 design pulses at 1 Hz"
! grep -q 'warning: the reserve' "$TMP/err" || fail "8 design pulses at 1 Hz: warned"
run "$SW" replay "$TMP/short.csv" --scene "$SRC/sample_logs/crate.ini" --settle 0 -q
! grep -q 'warning: the reserve' "$TMP/err" || fail "one design pulse: warned"

if "$SW" --help | grep -q monitor; then
    # At start, then after a reload that makes the scene stiff.
    cp "$SRC/sample_logs/crate.ini" "$TMP/m.ini"
    "$SW" monitor --scene "$TMP/frame.ini" --scene "$TMP/m.ini" --lcm-url memq:// \
        >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    sleep 1
    warned stiff-frame "monitor at start"
    grep -q 'scene crate-A needs' "$TMP/err" && fail "monitor: warned about crate-A"
    sed 's/stiff-frame/crate-A/' "$TMP/frame.ini" >"$TMP/m.ini.new"
    mv "$TMP/m.ini.new" "$TMP/m.ini"
    kill -HUP "$PID"
    i=0
    until grep -q 'reload: 1 of 2 packages rebuilt' "$TMP/err"; do
        i=$((i + 1))
        [ "$i" -lt 100 ] || fail "monitor: no reload"
        sleep 0.1
    done
    sleep 0.5
    kill -INT "$PID"
    wait "$PID" || true
    warned crate-A "monitor after a reload"
fi
echo "ok"
