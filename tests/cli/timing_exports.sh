#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# timing_exports.sh - the timing-shaped export files of tests/data/exports
# (made by mktiming.py; README.md there): merged CAN frames, event-driven
# rows, 1 kHz bursts in a 10 Hz log, a rate change, FIFO reads stamped in
# batches, 1600 Hz in whole milliseconds.  Each is an honest log: read
# with the sample crate, none of its rows may be refused, no gap may be
# noted, the verdict is given (the crate stays upright on all of them),
# and the repeated whole-ms stamps are said to be reconstructed.  The
# columns and units are given, so that this is about time alone.
. "$(dirname "$0")/lib.sh"
D=$SRC/tests/data/exports
SCENE=$SRC/sample_logs/crate.ini

# file, then the options that read it
check() {
    f=$1
    shift
    [ -r "$D/$f" ] || fail "$D/$f not found (python3 tests/data/exports/mktiming.py makes it)"
    run "$SW" replay "$D/$f" --scene "$SCENE" --time-col 1 "$@" --json
    expect_rc 0 "$f"
    if grep -qF "note: a gap" "$TMP/err"; then
        show
        fail "$f: a gap noted in an honest log"
    fi
    if grep -qE "leaps from|before the timeline|duplicate" "$TMP/err"; then
        show
        fail "$f: a row refused for its time"
    fi
    json_check "$TMP/out" 'j["samples_rejected"] == 0 and j["input"]["gaps"] == 0'
    json_check "$TMP/out" 'j["packages"][0]["verdict"] == "upright" and not j["packages"][0]["overturned"]'
    json_check "$TMP/out" 'j["input"]["check"] is None or "not resolved" in j["input"]["check"]'
}

check timing-can-merged.csv --accel-col 3 --time-unit s --accel-unit g
check timing-event-driven.csv --accel-col 2 --time-unit s --accel-unit m/s2
check timing-bursts.csv --accel-col 2 --time-unit s --accel-unit m/s2
check timing-rate-change.csv --accel-col 2 --time-unit s --accel-unit m/s2
check timing-fifo-batches.csv --accel-col 2 --time-unit us --accel-unit g
check timing-1600hz-whole-ms.csv --accel-col 2 --time-unit ms --accel-unit m/s2
expect_err "note: times repeat: the logger stamps whole units of 0.001 s" "whole-ms stamps"
expect_err "3000 of 8000 times reconstructed" "whole-ms stamps counted"
json_check "$TMP/out" 'j["samples_read"] == 8000 and abs(j["input"]["rate"] - 1600) < 16'

# The files are what mktiming.py writes.
python3 "$D/mktiming.py" "$TMP" || fail "mktiming.py"
for f in "$D"/timing-*.csv; do
    cmp -s "$f" "$TMP/$(basename "$f")" || fail "$(basename "$f") differs from what mktiming.py writes"
done
echo "ok"
