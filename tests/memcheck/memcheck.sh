#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# memcheck.sh - the swaywatch command under valgrind memcheck: no invalid
# read or write, no use of uninitialised memory, no leak.
#
#   sh memcheck.sh SWAYWATCH SOURCE_DIR WORK_DIR
#
# Runs replay on a sample drive (two packages, every output), on a log
# full of bad rows, and simulate.  Exit 77 (skipped) without valgrind.
set -eu
SW=$1
SRC=$2
WORK=$3
command -v valgrind >/dev/null 2>&1 || {
    echo "valgrind not found: skipped"
    exit 77
}
mkdir -p "$WORK"
VG="valgrind -q --error-exitcode=99 --leak-check=full --show-leak-kinds=definite,indirect,possible
    --errors-for-leak-kinds=definite,indirect,possible --track-origins=yes"
status=0

# vg NAME EXPECTED-EXIT ARGS...: the command under valgrind must end with
# its own exit status; 99 means valgrind found something.
vg() {
    name=$1
    want=$2
    shift 2
    set +e
    # shellcheck disable=SC2086
    $VG "$SW" "$@" >"$WORK/$name.out" 2>"$WORK/$name.err"
    rc=$?
    set -e
    if [ "$rc" -ne "$want" ]; then
        echo "FAIL $name: exit $rc, expected $want" >&2
        grep -v '^swaywatch: ' "$WORK/$name.err" | head -60 >&2
        status=1
    else
        echo "ok   $name"
    fi
}

LOGS=$SRC/sample_logs
SCENES=$SRC/tests/scenes
vg replay-sample 0 replay "$LOGS/braking-pothole.csv" --scene "$LOGS/crate.ini" \
    --scene "$LOGS/crate-on-frame.ini" --json --out "$WORK/state.csv" --events "$WORK/events.csv"
vg replay-bad-rows 0 replay "$SRC/tests/badinput/csv/many-rejects.csv" --force \
    --scene "$SCENES/crate-a-bare.ini" --scene "$SCENES/crate-a-frame.ini"
vg replay-nan-inf 0 replay "$SRC/tests/badinput/csv/nan-inf-1e400.csv" --force \
    --scene "$SCENES/crate-a-bare.ini" --json
vg replay-bad-scene 2 replay "$LOGS/braking-pothole.csv" \
    --scene "$SRC/tests/badinput/scenes/both-damping-zeta.ini"
vg simulate 0 simulate --scene "$SCENES/crate-a-frame.ini" --pulse half-sine --amplitude -8 \
    --omega 8 --out "$WORK/sim.csv"
exit $status
