#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SIGINT or SIGTERM in the middle of a long run: the command stops within
# a row, the output files end with a whole row, the summary is printed and
# marked INTERRUPTED, and the exit status is 130 (SIGINT) or 143 (SIGTERM).
# Runs are made long with a tiny --dt; the signal is sent once the state
# file has rows.
. "$(dirname "$0")/lib.sh"

SCENE=$SRC/sample_logs/crate.ini
python3 - >"$TMP/long.csv" <<'PY'
import math
print("t,a")
for i in range(100000):
    t = i * 0.001
    print(f"{t:.3f},{-5 * math.sin(7 * t):.4f}")
PY

# started WHAT CMD...: run CMD in the background ($PID), stdout in $TMP/out,
# stderr in $TMP/err; wait (at most 20 s) until $TMP/o.csv has 1000 bytes.
started() {
    what=$1
    shift
    rm -f "$TMP/o.csv" "$TMP/e.csv"
    "$@" >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    i=0
    while [ ! -f "$TMP/o.csv" ] || [ "$(wc -c <"$TMP/o.csv")" -lt 1000 ]; do
        i=$((i + 1))
        [ "$i" -lt 200 ] || fail "$what: no output after 20 s"
        kill -0 "$PID" 2>/dev/null || {
            show
            fail "$what: ended before the signal"
        }
        sleep 0.1
    done
}

# stopped SIG CODE WHAT: send SIG, expect exit CODE within 10 s
stopped() {
    kill -"$1" "$PID"
    i=0
    while kill -0 "$PID" 2>/dev/null; do
        i=$((i + 1))
        [ "$i" -lt 100 ] || {
            kill -9 "$PID"
            fail "$3: still running 10 s after $1"
        }
        sleep 0.1
    done
    set +e
    wait "$PID"
    RC=$?
    set -e
    expect_rc "$2" "$3"
}

# whole FILE FIELDS WHAT: every line of FILE has FIELDS fields; it ends
# with a newline
whole() {
    [ -s "$1" ] || fail "$3: $1 is empty"
    [ "$(tail -c 1 "$1" | od -An -c | tr -d ' ')" = '\n' ] || fail "$3: $1 is cut mid-row"
    awk -F, -v n="$2" 'NF != n { print FILENAME ":" NR ": " NF " fields"; bad = 1 }
                       END { exit bad }' "$1" || fail "$3: $1 has a cut row"
}

started replay "$SW" replay "$TMP/long.csv" --scene "$SCENE" --dt 1e-6 --out "$TMP/o.csv" \
    --events "$TMP/e.csv"
stopped INT 130 "replay CSV, SIGINT"
expect_err "interrupted by SIGINT" "replay CSV, SIGINT"
whole "$TMP/o.csv" 14 "replay CSV, SIGINT"
whole "$TMP/e.csv" 7 "replay CSV, SIGINT"
grep -q '^INTERRUPTED by SIGINT at t = ' "$TMP/out" || fail "replay: summary not marked"
grep -q 'outcome ' "$TMP/out" || fail "replay: no summary"

started replay "$SW" replay "$TMP/long.csv" --scene "$SCENE" --dt 1e-6 --out "$TMP/o.csv" --json
stopped TERM 143 "replay CSV --json, SIGTERM"
expect_err "interrupted by SIGTERM" "replay CSV --json, SIGTERM"
whole "$TMP/o.csv" 14 "replay CSV --json, SIGTERM"
json_check "$TMP/out" 'j["interrupted"]["signal"] == "SIGTERM" and j["interrupted"]["t"] > 0 and 0 < j["samples_read"] < 100000'

started simulate "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -4 --omega 0.25 \
    --dt 1e-7 --out "$TMP/o.csv"
stopped INT 130 "simulate, SIGINT"
expect_err "interrupted by SIGINT" "simulate, SIGINT"
whole "$TMP/o.csv" 14 "simulate, SIGINT"
grep -q '^INTERRUPTED by SIGINT' "$TMP/out" || fail "simulate: summary not marked"

started forensics "$SW" forensics "$TMP/long.csv" --scene "$SCENE" --dt 1e-6 --out "$TMP/o.csv"
stopped TERM 143 "forensics, SIGTERM"
expect_err "interrupted by SIGTERM" "forensics, SIGTERM"
whole "$TMP/o.csv" 14 "forensics, SIGTERM"
grep -q '^INTERRUPTED by SIGTERM' "$TMP/out" || fail "forensics: summary not marked"

# lcm-logger path (LCM builds)
if "$SW" --help | grep -q monitor && [ -n "${SW_LCM_TOOL:-}" ]; then
    "$SW_LCM_TOOL" mklog "$TMP/long.lcmlog" --rate 1000 --duration 100
    started "replay lcm" "$SW" replay "$TMP/long.lcmlog" --scene "$SCENE" --dt 1e-6 \
        --out "$TMP/o.csv" --events "$TMP/e.csv"
    stopped INT 130 "replay lcm-logger, SIGINT"
    expect_err "interrupted by SIGINT" "replay lcm-logger, SIGINT"
    whole "$TMP/o.csv" 14 "replay lcm-logger, SIGINT"
    whole "$TMP/e.csv" 7 "replay lcm-logger, SIGINT"
    grep -q '^INTERRUPTED by SIGINT' "$TMP/out" || fail "replay lcm: summary not marked"
fi

# boundary: the sweep writes nothing until it ends; a signal stops it at
# once, and no file is left.
"$SW" boundary --scene "$SCENE" --pulse full-sine --omega-ratio 1:12:0.01 --step 1e-4 \
    --dt 1e-6 --out "$TMP/b.csv" --no-progress >"$TMP/out" 2>"$TMP/err" &
PID=$!
sleep 1
kill -0 "$PID" 2>/dev/null || fail "boundary: ended before the signal"
stopped INT 130 "boundary, SIGINT"
expect_err "boundary: interrupted during the sweep; nothing written (SIGINT)" "boundary"
[ ! -e "$TMP/b.csv" ] || fail "boundary: a file was written"
echo "ok"
