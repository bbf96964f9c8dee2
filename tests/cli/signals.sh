#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SIGINT or SIGTERM in the middle of a long run: every command stops
# within a second (measured from the signal to the exit), the output files
# end with a whole row or record, the summary is printed and marked
# INTERRUPTED, and the exit status is 130 (SIGINT) or 143 (SIGTERM) (0
# for the live commands, monitor and watch).  Runs are made long with a
# tiny --dt; the signal is sent once the state file has rows.  Cases:
# replay (CSV, JSON, lcm-logger, the settling after the log), simulate,
# forensics, boundary, batch (its JSON Lines and CSV whole), monitor and
# watch (LCM builds).
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

# stopped SIG CODE WHAT: send SIG, expect exit CODE within a second
# (polled every 10 ms; a process still there after 10 s is killed)
stopped() {
    t0=$(date +%s%N)
    kill -"$1" "$PID"
    i=0
    while kill -0 "$PID" 2>/dev/null; do
        i=$((i + 1))
        [ "$i" -lt 1000 ] || {
            kill -9 "$PID"
            fail "$3: still running 10 s after $1"
        }
        sleep 0.01
    done
    ms=$((($(date +%s%N) - t0) / 1000000))
    set +e
    wait "$PID"
    RC=$?
    set -e
    echo "$3: stopped $ms ms after $1"
    [ "$ms" -le 1000 ] || fail "$3: took $ms ms to stop after $1 (at most 1000)"
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

# replay during the settling after the log: an undamped cushion rocks on
# for ever, --settle 1e5 would run for hours.
printf '[package]\nname = c\nheight = 2.0\nwidth = 0.728\nmass = 1000\n[cushion]\nomega = 40\n' \
    >"$TMP/undamped.ini"
python3 - >"$TMP/short.csv" <<'PY'
import math
print("t,a")
for i in range(500):
    print(f"{i * 0.001:.3f},{-3 * math.sin(math.pi * i / 500):.4f}")
PY
started "replay settle" "$SW" replay "$TMP/short.csv" --scene "$TMP/undamped.ini" --settle 1e5 \
    --out "$TMP/o.csv" --events "$TMP/e.csv"
sleep 1 # the log (0.5 s) is done: settling
stopped TERM 143 "replay --settle 1e5, SIGTERM while settling"
whole "$TMP/o.csv" 14 "replay settling, SIGTERM"
grep -q '^INTERRUPTED by SIGTERM at t = ' "$TMP/out" || fail "replay settling: summary not marked"

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

# batch: the logs done have their records, whole, in order; the others
# none.  Logs of equal size run in order, one thread; the signal comes
# once 8 KiB of records were written (more than a stdio buffer: a process
# killed then leaves a record cut).
python3 - "$TMP" <<'PY'
import math, sys
rows = "".join(f"{i * 0.001:.3f},{-5 * math.sin(7 * i * 0.001):.4f}\n" for i in range(3000))
for k in range(200):
    open(f"{sys.argv[1]}/b{k:03d}.csv", "w").write("t,a\n" + rows)
PY
for sig in TERM INT; do
    code=143
    [ "$sig" = INT ] && code=130
    rm -f "$TMP/o.jsonl" "$TMP/o.csv"
    "$SW" batch "$TMP"/b[0-9]*.csv --scene "$SCENE" --scene "$SRC/sample_logs/crate-on-frame.ini" \
        --dt 1e-4 --threads 1 -o "$TMP/o.jsonl" --csv "$TMP/o.csv" >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    i=0
    while [ ! -f "$TMP/o.jsonl" ] || [ "$(wc -c <"$TMP/o.jsonl")" -lt 8192 ]; do
        i=$((i + 1))
        [ "$i" -lt 600 ] || fail "batch: not 8 KiB of records after 60 s"
        sleep 0.1
    done
    kill -0 "$PID" 2>/dev/null || fail "batch: ended before the signal"
    stopped "$sig" "$code" "batch, SIG$sig"
    python3 - "$TMP" "$TMP/err" <<'PY' || fail "batch, SIG$sig: records not whole"
import csv, json, re, sys
t = sys.argv[1]
raw = open(t + "/o.jsonl", "rb").read()
assert raw.endswith(b"\n"), "the JSON Lines end mid-record"
recs = [json.loads(l) for l in raw.decode().splitlines()]
rows = list(csv.reader(open(t + "/o.csv", newline="")))
assert all(len(r) == len(rows[0]) for r in rows), "a CSV row is cut"
assert len(rows) - 1 == len(recs), "%d rows, %d records" % (len(rows) - 1, len(recs))
m = re.search(r"(\d+) of 200 logs done, their (\d+) records? written whole",
              open(sys.argv[2]).read())
assert m, "no summary"
done, n = int(m.group(1)), int(m.group(2))
assert n == len(recs) == 2 * done, (n, len(recs), done)
assert 3 <= done < 200, "done %d: not interrupted mid-batch" % done
idx = [r["index"] for r in recs]
assert idx == sorted(idx) and all(r["status"] == "ok" for r in recs), idx
print("batch: %d logs done, %d records" % (done, len(recs)))
PY
    expect_err "batch: interrupted by SIG$sig: " "batch, SIG$sig"
done

# The live commands (LCM builds), on memq:// (no network): they run until
# the signal, then exit 0 within a second.
if "$SW" --help | grep -q '^  monitor'; then
    "$SW" monitor -l memq:// --scene "$SCENE" >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    sleep 1
    stopped TERM 0 "monitor, SIGTERM"
    "$SW" monitor -l memq:// --scene "$SCENE" >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    sleep 1
    stopped INT 0 "monitor, SIGINT"
fi
if "$SW" --help | grep -q '^  watch'; then
    "$SW" watch -l memq:// --every 30 >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    sleep 1
    stopped TERM 0 "watch (plain snapshots), SIGTERM"
    "$SW" watch -l memq:// --once --wait 60 >"$TMP/out" 2>"$TMP/err" &
    PID=$!
    sleep 1
    stopped INT 0 "watch --once, SIGINT"
fi
echo "ok"
