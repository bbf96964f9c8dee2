#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Scenes inside every documented limit that the engine runs slower than
# real time (a frame of 1e7 kg on bearings of 1e6 rad/s with no damping,
# alone or under a cushion of 1e6 rad/s with a cubic term of 1e30) are
# measured when loaded and warned about with the factor measured; the
# monitor warns at start and after a reload that brings one in.  Ordinary
# scenes run hundreds of times faster than real time: no warning.
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
zeta = 1e-300
INI
cp "$TMP/frame.ini" "$TMP/both.ini"
cat >>"$TMP/both.ini" <<'INI'
[cushion]
omega = 1e6
zeta = 0.05
cubic = 1e30
INI
sed -i 's/stiff-frame/stiff-both/' "$TMP/both.ini"
printf 't,a\n0,0\n0.001,-1\n0.002,0\n' >"$TMP/short.csv"
WARN='warning: scene %s runs at only [0-9.e+-]* times real time (measured on 0.05 s of rocking input)'

# warned NAME WHAT: stderr has the warning for scene NAME, with a factor < 10
warned() {
    # shellcheck disable=SC2059
    grep -q "^swaywatch: $(printf "$WARN" "$1")" "$TMP/err" || {
        show
        fail "$2: no warning naming the factor"
    }
    f=$(sed -n "s/.*scene $1 runs at only \([0-9.e+-]*\) times.*/\1/p" "$TMP/err" | head -1)
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
run "$SW" replay "$TMP/short.csv" --scene "$SRC/sample_logs/crate.ini" \
    --scene "$SRC/sample_logs/crate-on-frame.ini" --scene "$SRC/sample_logs/crate-on-cushion.ini" \
    --settle 0 -q
expect_rc 0 "ordinary scenes"
! grep -q 'real time' "$TMP/err" || fail "ordinary scenes: warned"

if "$SW" --help | grep -q monitor; then
    # At start, then after a reload that makes the scene stiff.
    cp "$SRC/sample_logs/crate.ini" "$TMP/m.ini"
    "$SW" monitor --scene "$TMP/frame.ini" --scene "$TMP/m.ini" --lcm-url memq:// \
        >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    sleep 1
    warned stiff-frame "monitor at start"
    grep -q 'scene crate-A runs' "$TMP/err" && fail "monitor: warned about crate-A"
    sed 's/stiff-frame/crate-A/' "$TMP/frame.ini" >"$TMP/m.ini"
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
