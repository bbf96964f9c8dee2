#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A run in which a package's model faulted never reports a plain verdict:
# the summary says "not a verdict", the JSON has "verdict": "unreliable"
# with the faults, and --fail-on-overturn exits 2 instead of 0.  The
# faults come from input the model cannot take: 20 ms of a 6 g shock in
# a braking shock under --dt 0.5 (a step RK4 takes on the crate's rocking,
# but not on that input).  The bed in free fall (vertical acceleration
# below -g) is no fault: the crate flies (tests/cli/flight.sh).  Nor does
# a run whose input has a hole over motion: its verdict is "incomplete".
. "$(dirname "$0")/lib.sh"

SCENE=$SRC/sample_logs/crate.ini
python3 - >"$TMP/fall.csv" <<'PY'
print("t,ax,az")
for i in range(2000):
    t = i * 0.001
    ax = -5.0 if 0.2 < t < 0.6 else 0.0
    az = -12.0 if 0.3 < t < 0.32 else 0.0
    print(f"{t:.3f},{ax},{az}")
PY
python3 - >"$TMP/shock.csv" <<'PY'
print("t,ax")
for i in range(2000):
    t = i * 0.001
    ax = -60.0 if 0.3 < t < 0.32 else -5.0 if 0.2 < t < 0.6 else 0.0
    print(f"{t:.3f},{ax}")
PY

run "$SW" replay "$TMP/fall.csv" --scene "$SCENE" --vert-col az --json
expect_rc 0 "replay of a log in free fall"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "upright" and j["packages"][0]["faults"] == 0 and j["packages"][0]["flights"] == 1'

run "$SW" replay "$TMP/shock.csv" --scene "$SCENE" --dt 0.5
expect_rc 0 "replay of a log that faults the model"
grep -q 'outcome         stayed upright (model faulted [0-9]* times: not a verdict' "$TMP/out" || {
    show
    fail "the summary gives a plain verdict"
}
run "$SW" replay "$TMP/shock.csv" --scene "$SCENE" --dt 0.5 --json
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "unreliable" and j["packages"][0]["faults"] > 0 and not j["packages"][0]["overturned"]'
run "$SW" replay "$TMP/shock.csv" --scene "$SCENE" --dt 0.5 --fail-on-overturn -q
expect_rc 2 "--fail-on-overturn on a faulted run"
expect_err "crate-A: the model faulted" "--fail-on-overturn on a faulted run"
expect_err "no verdict" "--fail-on-overturn on a faulted run"
run "$SW" forensics "$TMP/shock.csv" --scene "$SCENE" --dt 0.5 --no-what-if --fail-on-overturn -q
expect_rc 2 "forensics --fail-on-overturn on a faulted run"

# Runs without faults keep their plain verdicts and exits.
run "$SW" replay "$SRC/sample_logs/braking-pothole.csv" --scene "$SCENE" --json --fail-on-overturn
expect_rc 0 "upright"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "upright" and j["packages"][0]["faults"] == 0'
run "$SW" replay "$SRC/sample_logs/hard-stop-overturn.csv" --scene "$SCENE" --json --fail-on-overturn
expect_rc 1 "overturned"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "overturned"'
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude -9 --omega 10 --json
json_check "$TMP/out" 'j["packages"][0]["verdict"] in ("upright", "overturned")'

# Incomplete is a verdict.  A 2 s hole over the braking of the sample drive
# (6.5 s to 8.5 s; the crate lifts at 6.78 s): what the hole hid may have
# overturned it, so neither the text, the JSON, batch's records nor the
# exit code may read as upright; what the run saw is kept beside it.
awk -F, 'NR == 1 || !($1 > 6.5 && $1 < 8.5)' "$SRC/sample_logs/braking-pothole.csv" >"$TMP/hole.csv"
run "$SW" replay "$TMP/hole.csv" --scene "$SCENE"
expect_rc 0 "replay of a log with a hole over the braking"
grep -q 'outcome         INCOMPLETE: upright as far as the samples go, but a gap of 2 s at 6.500 s overlapped rocking' "$TMP/out" || {
    show
    fail "the summary does not say INCOMPLETE with the gap"
}
grep -q 'stayed upright' "$TMP/out" && fail "the summary of an incomplete run says 'stayed upright'"
run "$SW" replay "$TMP/hole.csv" --scene "$SCENE" --json --fail-on-overturn
expect_rc 1 "--fail-on-overturn on an incomplete verdict"
expect_err "the verdict is incomplete: a gap of 2 s at 6.500 s" "--fail-on-overturn, incomplete"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "incomplete" and j["packages"][0]["seen"] == "upright" and not j["packages"][0]["overturned"] and j["input"]["incomplete"]'
json_check "$TMP/out" 'j["packages"][0]["incomplete_because"]["count"] == 1 and j["packages"][0]["incomplete_because"]["first_kind"] == "gap" and abs(j["packages"][0]["incomplete_because"]["first_span"] - 2.0) < 1e-9 and abs(j["packages"][0]["incomplete_because"]["first_time"] - 6.5) < 1e-9'
run "$SW" forensics "$TMP/hole.csv" --scene "$SCENE" --no-what-if --fail-on-overturn --json
expect_rc 1 "forensics --fail-on-overturn on an incomplete verdict"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "incomplete" and j["packages"][0]["seen"] == "upright" and j["replay"]["packages"][0]["verdict"] == "incomplete"'
run "$SW" forensics "$TMP/hole.csv" --scene "$SCENE" --no-what-if -q
grep -q '^crate-A (.*): INCOMPLETE: upright as far as the samples go' "$TMP/out" || {
    show
    fail "forensics' answer does not say INCOMPLETE"
}
# batch: the record's status and verdict, the table's, and the exit code
run "$SW" batch "$TMP/hole.csv" "$SRC/sample_logs/braking-pothole.csv" --scene "$SCENE" \
    --csv "$TMP/hole-b.csv" -o "$TMP/hole-b.jsonl" -q --fail-on-overturn
expect_rc 1 "batch --fail-on-overturn with an incomplete verdict"
python3 - "$TMP/hole-b.jsonl" "$TMP/hole-b.csv" <<'PY' || fail "batch records of an incomplete verdict"
import csv, json, sys
recs = [json.loads(l) for l in open(sys.argv[1])]
rows = list(csv.DictReader(open(sys.argv[2])))
assert [(r["status"], r["verdict"], r["seen"]) for r in recs] == [
    ("incomplete", "incomplete", "upright"), ("ok", "upright", "upright")], recs
assert [(r["status"], r["verdict"]) for r in rows] == [
    ("incomplete", "incomplete"), ("ok", "upright")], rows
PY
run "$SW" batch "$TMP/hole.csv" --job forensics --no-what-if --scene "$SCENE" -q
json_check "$TMP/out" 'j["status"] == "incomplete" and j["verdict"] == "incomplete"'

# An overturn seen is one, gaps or not: a 0.1 s hole in the shock of the
# hard stop leaves the input incomplete, and the crate still overturns.
awk -F, 'NR == 1 || !($1 > 3.0 && $1 < 3.1)' "$SRC/sample_logs/hard-stop-overturn.csv" >"$TMP/ohole.csv"
run "$SW" replay "$TMP/ohole.csv" --scene "$SCENE" --json --fail-on-overturn
expect_rc 1 "an overturn with a gap"
json_check "$TMP/out" 'j["input"]["incomplete"] and j["packages"][0]["verdict"] == "overturned" and j["packages"][0]["incomplete_because"] is None'
echo "ok"
