# SPDX-License-Identifier: GPL-3.0-or-later
# csv.sh - replay of CSV logs end to end: bad rows, --strict, stdin, the
# JSON contract, the state and event files, and the CSV options.
. "$(dirname "$0")/lib.sh"
SCENE=$SRC/sample_logs/crate.ini
FRAME=$SRC/sample_logs/crate-on-frame.ini
LOGS=$SRC/sample_logs

# A 2 s log at 1 kHz: a braking half-sine strong enough to rock the crate,
# with a bad row (line 502), a row whose time goes back (line 1003) and a
# non-finite value (line 1504).
awk 'BEGIN {
    print "t,a";
    for (i = 0; i <= 2000; i++) {
        t = i / 1000.0; a = (t < 0.5) ? -6 * sin(3.14159265 * t / 0.5) : 0;
        line = i + 2;
        if (line == 502) { print t ",abc"; continue }
        if (line == 1003) { print "0.25," a; continue }
        if (line == 1504) { print t ",nan"; continue }
        printf "%.3f,%.6f\n", t, a
    }
}' >"$TMP/bad.csv"

run "$SW" replay "$TMP/bad.csv" --scene "$SCENE" --json
expect_rc 0 "log with bad rows"
cp "$TMP/out" "$TMP/bad.json"
expect_err "swaywatch: $TMP/bad.csv:502: " "bad number reported with its line"
expect_err "swaywatch: $TMP/bad.csv:1003: " "time going back reported with its line"
expect_err "swaywatch: $TMP/bad.csv:1504: " "nan reported with its line"
# and how the columns were read: the header's names, units by default
expect_err "swaywatch: $TMP/bad.csv: time: column 1 \"t\", s (default); accel: column 2 \"a\", m/s^2 (default)" \
    "the columns chosen"
[ "$(wc -l <"$TMP/err")" -eq 4 ] || { show; fail "expected exactly 4 lines on stderr"; }
json_check "$TMP/bad.json" 'j["samples_read"] == 2001 and j["samples_rejected"] == 3'
json_check "$TMP/bad.json" 'j["packages"][0]["samples_rejected"] == 3'
# The rest was processed: the pulse made the crate rock.
json_check "$TMP/bad.json" 'j["packages"][0]["uplift_time"] is not None and j["packages"][0]["impacts"] > 0'

# --strict: the first rejected row ends the run with exit 2.
run "$SW" replay "$TMP/bad.csv" --scene "$SCENE" --strict --json
expect_rc 2 "--strict"
expect_err "swaywatch: $TMP/bad.csv:502: " "--strict names the first bad row"
[ "$(grep -vc 'time: column' "$TMP/err")" -eq 2 ] || { show; fail "--strict: expected the bad row and the stop message"; }
expect_err "stopped at the first rejected row (--strict)" "--strict says why it stopped"
[ ! -s "$TMP/out" ] || fail "--strict printed a summary"

# More than 20 bad rows: 20 listed, the rest counted.
awk 'BEGIN { print "t,a"; for (i = 0; i < 100; i++) { if (i % 4 == 1) print i/100 ",x"; else print i/100 ",0.5" } }' >"$TMP/many.csv"
# A quarter of the rows refused: no verdict (more than --max-rejected,
# 1 %), unless the limit is raised, or the verdict forced and marked.
run "$SW" replay "$TMP/many.csv" --scene "$SCENE" --json
expect_rc 2 "many bad rows: no verdict"
[ ! -s "$TMP/out" ] || fail "a summary for a refused log"
expect_err "no verdict: 25 of 100 samples (25.0 %) were refused, more than 1 %" "why no verdict"
expect_err "--force" "the way out named"
run "$SW" replay "$TMP/many.csv" --scene "$SCENE" --json --max-rejected 30
expect_rc 0 "many bad rows, --max-rejected 30"
[ "$(grep -c ':[0-9]*: ' "$TMP/err")" -eq 20 ] || { show; fail "expected 20 listed rows"; }
expect_err "swaywatch: $TMP/many.csv: ... 5 more rejected rows" "the rest counted"
json_check "$TMP/out" 'j["samples_read"] == 100 and j["samples_rejected"] == 25'
json_check "$TMP/out" 'j["input"]["forced"] == False and abs(j["input"]["rejected_share"] - 0.25) < 1e-12'
run "$SW" replay "$TMP/many.csv" --scene "$SCENE" --json --force
expect_rc 0 "many bad rows, --force"
json_check "$TMP/out" 'j["input"]["forced"] == True and "refused" in j["input"]["check"]'
run "$SW" replay "$TMP/many.csv" --scene "$SCENE" --quiet --max-rejected 30
expect_rc 0 "--quiet"
[ ! -s "$TMP/out" ] || fail "--quiet printed a summary"
[ "$(wc -l <"$TMP/err")" -eq 1 ] || { show; fail "--quiet: expected one count line"; }
expect_err "25 rejected rows" "--quiet counts"

# Standard input gives the same answer as the file.
run "$SW" replay - --scene "$SCENE" --json <"$TMP/bad.csv"
expect_rc 0 "stdin"
cp "$TMP/out" "$TMP/stdin.json"
expect_err "(stdin):502: " "stdin rows named (stdin)"
python3 - "$TMP/bad.json" "$TMP/stdin.json" <<'PY' || fail "stdin and file differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
a.pop("log"); b.pop("log")
sys.exit(0 if a == b else 1)
PY

# The JSON contract, for two packages.
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$SCENE" --scene "$FRAME" --json \
    --out "$TMP/state.csv" --events "$TMP/events.csv"
expect_rc 0 "two packages"
cp "$TMP/out" "$TMP/two.json"
json_check "$TMP/two.json" 'isinstance(j["swaywatch"], str) and j["log"].endswith("braking-pothole.csv")'
json_check "$TMP/two.json" 'j["samples_read"] == 20001 and j["samples_rejected"] == 0'
json_check "$TMP/two.json" '[p["model"] for p in j["packages"]] == ["bare", "frame"]'
json_check "$TMP/two.json" '[p["name"] for p in j["packages"]] == ["crate-A", "crate-A-on-frame"]'
json_check "$TMP/two.json" 'all(set(["name", "model", "overturned", "overturn_time", "tip_time", "max_abs_theta", "max_theta_ratio", "min_margin", "uplift_time", "impacts", "samples_read", "samples_rejected", "scheme", "dt"]) <= set(p) for p in j["packages"])'
json_check "$TMP/two.json" 'all(isinstance(p["overturned"], bool) and isinstance(p["impacts"], int) and p["dt"] > 0 for p in j["packages"])'
json_check "$TMP/two.json" 'all((p["overturn_time"] is None) == (not p["overturned"]) for p in j["packages"])'
# No NaN or Infinity anywhere (Python's json accepts them, so look).
grep -Eqi 'nan|infinity' "$TMP/two.json" && fail "NaN or Infinity in the JSON"

# The state series: header, one row per sample and package, only finite numbers.
[ "$(head -1 "$TMP/state.csv")" = "t,package,phase,theta,theta_dot,u,u_dot,z,z_dot,margin,margin_bound,uplift_ratio,a_g,reserve_g" ] ||
    fail "--out header"
tail -n +2 "$TMP/state.csv" | grep -Eqi 'nan|inf' && fail "--out holds nan or inf"
rows=$(grep -c ',crate-A,' "$TMP/state.csv")
[ "$rows" -ge 20001 ] || fail "--out: $rows rows for crate-A, expected one per sample"
awk -F, 'NR > 1 && NF != 14 { bad = 1 } END { exit bad }' "$TMP/state.csv" || fail "--out: rows without 14 fields"
[ "$(head -1 "$TMP/events.csv")" = "t,package,event,theta,theta_dot,margin,info" ] || fail "--events header"
grep -q ',crate-A,uplift,' "$TMP/events.csv" || fail "--events: no uplift of crate-A"
tail -n +2 "$TMP/events.csv" | grep -Eqi 'nan|inf' && fail "--events holds nan or inf"
# The event list agrees with the summary: every impact of the engine is a
# row of its own or counted in a settling row (info: how many it folds).
python3 - "$TMP/two.json" "$TMP/events.csv" <<'PY' || fail "events and summary disagree"
import csv, json, sys
j = json.load(open(sys.argv[1]))
ev = list(csv.DictReader(open(sys.argv[2])))
for p in j["packages"]:
    n = sum(1 for e in ev if e["package"] == p["name"] and e["event"] == "impact")
    folded = sum(int(e["info"]) for e in ev if e["package"] == p["name"] and e["event"] == "settling")
    if n + folded != p["impacts"] or n < p["significant_impacts"]:
        print(p["name"], n, folded, p["impacts"], p["significant_impacts"], file=sys.stderr)
        sys.exit(1)
PY

# --every 10 keeps one row in ten.
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$SCENE" --quiet --settle 0 --every 10 --out "$TMP/every.csv"
expect_rc 0 "--every 10"
rows=$(($(wc -l <"$TMP/every.csv") - 1))
[ "$rows" -eq 2001 ] || fail "--every 10: $rows rows, expected 2001"

# ';' + ms + g gives the same result as ',' + s + m/s^2 (same data).
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$SCENE" --json
cp "$TMP/out" "$TMP/si.json"
run "$SW" replay "$LOGS/braking-pothole-g-ms.csv" --scene "$SCENE" --json \
    --delimiter ';' --time-unit ms --accel-unit g --time-col time_ms --accel-col accel_g
expect_rc 0 "g/ms/; variant"
cp "$TMP/out" "$TMP/gms.json"
python3 - "$TMP/si.json" "$TMP/gms.json" <<'PY' || fail "units variant differs"
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["samples_read"] == b["samples_read"] == 20001, (a["samples_read"], b["samples_read"])
assert a["samples_rejected"] == b["samples_rejected"] == 0
for p, q in zip(a["packages"], b["packages"]):
    for k in p:
        x, y = p[k], q[k]
        if isinstance(x, float) and isinstance(y, float):
            assert math.isclose(x, y, rel_tol=1e-6, abs_tol=1e-9), (k, x, y)
        else:
            assert x == y, (k, x, y)
PY

# --flip mirrors the axis: braking becomes speeding up, the crate rocks backward.
run "$SW" replay "$TMP/bad.csv" --scene "$SCENE" --events "$TMP/noflip.csv" --quiet
expect_rc 0 "braking pulse"
awk -F, '$3 == "uplift" { print $7; exit }' "$TMP/noflip.csv" | grep -qx '1' || fail "braking: first uplift not forward (+1)"
run "$SW" replay "$TMP/bad.csv" --scene "$SCENE" --flip --events "$TMP/flip.csv" --quiet
expect_rc 0 "--flip"
awk -F, '$3 == "uplift" { print $7; exit }' "$TMP/flip.csv" | grep -qx -- '-1' || fail "--flip: first uplift not backward (-1)"

# A header-less file, columns by index, tab delimited.
awk 'BEGIN { for (i = 0; i <= 1000; i++) printf "x\t%.6f\t%.3f\n", -6 * (i < 500) * sin(3.14159265 * i / 500), i / 1000.0 }' >"$TMP/tab.tsv"
run "$SW" replay "$TMP/tab.tsv" --scene "$SCENE" --no-header --delimiter tab --time-col 3 --accel-col 2 --json
expect_rc 0 "tab, no header, columns by index"
json_check "$TMP/out" 'j["samples_read"] == 1001 and j["samples_rejected"] == 0 and j["packages"][0]["impacts"] > 0'

# A column name that is not in the header is bad input.
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$SCENE" --accel-col no_such_column
expect_rc 2 "unknown column name"
expect_prefixed_err "unknown column name"

# One row whose time is off (0.100 written 900.100) is that row's fault:
# the rows after it are kept, the verdict is the whole log's (the crate
# overturns, as on the log as recorded), the row is named.
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$SCENE" --json
expect_rc 0 "hard stop as recorded"
json_check "$TMP/out" 'j["packages"][0]["overturned"]'
awk -F, '$1 == "0.100" { print "900.100," $2; next } { print }' \
    "$LOGS/hard-stop-overturn.csv" >"$TMP/one-bad-time.csv"
grep -q '^900.100,' "$TMP/one-bad-time.csv" || fail "no row at 0.100 s to spoil"
run "$SW" replay "$TMP/one-bad-time.csv" --scene "$SCENE" --fail-on-overturn
expect_rc 1 "one row off in time: the overturn is still seen"
expect_err "one-bad-time.csv:102: time 900.1 s leaps" "the row off in time is named"
grep -q "1 rejected" "$TMP/out" || { show; fail "one row off in time: not exactly one row rejected"; }

# A corrupt time in the first line is a rejected row, not a header.
printf '0.00O,-9\n0.001,-9\n0.002,-9\n' >"$TMP/corrupt-first.csv"
run "$SW" replay "$TMP/corrupt-first.csv" --scene "$SCENE" --force --json
expect_err "corrupt-first.csv:1: time (column 1) is not a number" "corrupt first row"
json_check "$TMP/out" 'j["samples_read"] == 3 and j["samples_rejected"] == 1'

# An empty log has no samples.
: >"$TMP/empty.csv"
run "$SW" replay "$TMP/empty.csv" --scene "$SCENE"
expect_rc 2 "empty log"
expect_prefixed_err "empty log"
echo "ok"
