#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A run in which a package's model faulted never reports a plain verdict:
# the summary says "not a verdict", the JSON has "verdict": "unreliable"
# with the faults, and --fail-on-overturn exits 2 instead of 0.  The
# faults come from input the model cannot take: the bed in free fall
# (vertical acceleration below -g) for 20 ms of a braking shock.
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

run "$SW" replay "$TMP/fall.csv" --scene "$SCENE" --vert-col az
expect_rc 0 "replay of a log that faults the model"
grep -q 'outcome         stayed upright (model faulted [0-9]* times: not a verdict' "$TMP/out" || {
    show
    fail "the summary gives a plain verdict"
}
run "$SW" replay "$TMP/fall.csv" --scene "$SCENE" --vert-col az --json
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "unreliable" and j["packages"][0]["faults"] > 0 and not j["packages"][0]["overturned"]'
run "$SW" replay "$TMP/fall.csv" --scene "$SCENE" --vert-col az --fail-on-overturn -q
expect_rc 2 "--fail-on-overturn on a faulted run"
expect_err "crate-A: the model faulted" "--fail-on-overturn on a faulted run"
expect_err "no verdict" "--fail-on-overturn on a faulted run"
run "$SW" forensics "$TMP/fall.csv" --scene "$SCENE" --vert-col az --no-what-if --fail-on-overturn -q
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
echo "ok"
