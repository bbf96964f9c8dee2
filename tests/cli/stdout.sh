# SPDX-License-Identifier: GPL-3.0-or-later
# stdout.sh - '-' as an output file is standard output: --out - and
# --events - write there (and create no file named '-'), the same bytes as
# into a file; refused when both are '-' or when a summary goes there too.
. "$(dirname "$0")/lib.sh"
SCENE=$SRC/sample_logs/crate.ini
LOG=$SRC/sample_logs/braking-pothole.csv
cd "$TMP"

run "$SW" replay "$LOG" --scene "$SCENE" --out "$TMP/states.csv" --events "$TMP/events.csv" -q
expect_rc 0 "replay into files"
run "$SW" replay "$LOG" --scene "$SCENE" --out - --events "$TMP/events2.csv" -q
expect_rc 0 "replay --out -"
cmp -s "$TMP/out" "$TMP/states.csv" || fail "--out - differs from --out FILE"
cmp -s "$TMP/events2.csv" "$TMP/events.csv" || fail "--events FILE beside --out -"
run "$SW" replay "$LOG" --scene "$SCENE" --events - -q
expect_rc 0 "replay --events -"
cmp -s "$TMP/out" "$TMP/events.csv" || fail "--events - differs from --events FILE"
[ ! -e "$TMP/-" ] || fail "a file named '-' was created"

run "$SW" replay "$LOG" --scene "$SCENE" --out - --events - -q
expect_rc 2 "--out - --events -"
expect_err "cannot both be standard output" "--out - --events -"
run "$SW" replay "$LOG" --scene "$SCENE" --out -
expect_rc 2 "--out - with the human summary"
expect_err "add -q" "--out - with the human summary"
[ ! -s "$TMP/out" ] || fail "--out - with the summary wrote to stdout"
run "$SW" replay "$LOG" --scene "$SCENE" --events - --json -q
expect_rc 2 "--events - with --json"
expect_err "JSON summary" "--events - with --json"

run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -8 --omega 4 --duration 1 \
    --out - -q
expect_rc 0 "simulate --out -"
head -1 "$TMP/out" | grep -q '^t,package,phase,' || fail "simulate --out -: no header"
run "$SW" forensics "$LOG" --scene "$SCENE" --no-what-if --events - -q
expect_rc 0 "forensics --events -"
cmp -s "$TMP/out" "$TMP/events.csv" || fail "forensics --events - differs from replay's"
run "$SW" forensics "$LOG" --scene "$SCENE" --no-what-if --out -
expect_rc 2 "forensics --out - with the summary"

# boundary: the curves go to standard output unless --out names a file;
# one of its CSV files may take it then.
run "$SW" boundary --scene "$SCENE" --pulse half-sine --omega-ratio 2,3 --out - -q
expect_rc 0 "boundary --out -"
head -1 "$TMP/out" | grep -q '^omega_ratio,' || fail "boundary --out -: no header"
run "$SW" boundary --scene "$SCENE" --pulse half-sine --omega-ratio 2,3 --out "$TMP/b.csv" \
    --detail - -q
expect_rc 0 "boundary --detail -"
head -1 "$TMP/out" | grep -q '^curve,omega_ratio,found,' || fail "boundary --detail -: no header"
run "$SW" boundary --scene "$SCENE" --pulse half-sine --omega-ratio 2,3 --detail -
expect_rc 2 "boundary --detail - beside the curves"
[ ! -e "$TMP/-" ] || fail "a file named '-' was created"
echo "ok"
