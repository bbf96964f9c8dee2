# forensics.sh - "swaywatch forensics": the replay summary, the safety
# factor (<= 1 for a log that overturned, > 1 for one that did not, and
# scaling the log by it -1 % / +1 % flips the outcome of replay), the
# what-if table, JSON and the figure.
. "$(dirname "$0")/lib.sh"
LOGS=$SRC/sample_logs
CRATE=$LOGS/crate.ini

run "$SW" forensics --help
expect_rc 0 "forensics --help"
[ ! -s "$TMP/err" ] || fail "forensics --help wrote to stderr"
for opt in --scene --settle --frame-mass --frame-omega --frame-zeta --cushion-omega \
    --cushion-zeta --size --plot --json --threads --time-col --accel-unit 'Exit codes: 0 ok'; do
    grep -q -- "$opt" "$TMP/out" || fail "forensics --help: $opt not listed"
done
run "$SW" forensics --scene "$CRATE"
expect_rc 2 "no LOG"
expect_prefixed_err "no LOG"
run "$SW" forensics "$TMP/none.csv" --scene "$CRATE"
expect_rc 3 "missing LOG"
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --size 2by1
expect_rc 2 "bad --size"
expect_err "--size" "bad --size"
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --scene "$CRATE"
expect_rc 2 "two scenes"

# scale LOG FACTOR OUT: the log with its acceleration column times FACTOR
scale() {
    python3 - "$1" "$2" "$3" <<'PY'
import sys
src, f, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
with open(src) as i, open(out, "w") as o:
    o.write(i.readline())
    for line in i:
        t, a = line.strip().split(",")
        o.write("%s,%.17g\n" % (t, f * float(a)))
PY
}

# check LOG OVERTURNED: the safety factor is on the right side of 1 and
# replay of the log scaled by 0.99 / 1.01 of it stays up / overturns
check() {
    run "$SW" forensics "$1" --scene "$CRATE" --json --no-what-if
    expect_rc 0 "forensics $1"
    cp "$TMP/out" "$TMP/f.json"
    json_check "$TMP/f.json" "j['replay']['packages'][0]['overturned'] == $2 and j['safety_factor']['overturned'] == $2"
    if [ "$2" = True ]; then
        json_check "$TMP/f.json" 'j["safety_factor"]["factor"] <= 1'
    else
        json_check "$TMP/f.json" 'j["safety_factor"]["factor"] > 1'
    fi
    f=$(python3 -c 'import json,sys; print(repr(json.load(open(sys.argv[1]))["safety_factor"]["factor"]))' "$TMP/f.json")
    for k in 0.99 1.01; do
        scale "$1" "$(python3 -c "print(repr($k * $f))")" "$TMP/s.csv"
        run "$SW" replay "$TMP/s.csv" --scene "$CRATE" --json
        expect_rc 0 "replay x$k"
        cp "$TMP/out" "$TMP/r$k.json"
    done
    json_check "$TMP/r0.99.json" 'not j["packages"][0]["overturned"]'
    json_check "$TMP/r1.01.json" 'j["packages"][0]["overturned"]'
}
check "$LOGS/hard-stop-overturn.csv" True
check "$LOGS/braking-pothole.csv" False

# The human report: replay's summary, the factor, the what-if table; the
# cushion row is computed, or says why not (a build without the cushion
# model), never an error.
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" --frame-omega 3 \
    --cushion-omega 60 --size 2.4x0.8
expect_rc 0 "what-if"
for want in 'package crate-A: bare model' 'minimum margin' 'safety factor' 'what if' 'as given' \
    'frame ' 'cushion ' 'size 2.4x0.8 m'; do
    grep -qF "$want" "$TMP/out" || { show; fail "report lacks '$want'"; }
done
cushion=$(grep '^  cushion ' "$TMP/out")
case "$cushion" in
*"n/a: cushion model not in this build"*) ;;
*upright* | *OVERTURNED*) ;;
*) show; fail "cushion row: $cushion" ;;
esac
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE"
grep -qF 'no frame given' "$TMP/out" || { show; fail "frame row without parameters"; }

# JSON: one object, the replay summary inside, a row per case
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$LOGS/crate-on-frame.ini" --json \
    --size 1.5x0.728 --threads 1
expect_rc 0 "json"
cp "$TMP/out" "$TMP/one.json"
json_check "$TMP/one.json" '[c["case"] for c in j["what_if"]] == ["as given", "bed", "cushion", "size 1.5x0.728 m"]'
json_check "$TMP/one.json" 'j["what_if"][0]["model"] == "frame" and j["what_if"][1]["model"] == "bare" and not j["what_if"][2]["available"]'
grep -Eqi 'nan|infinity' "$TMP/one.json" && fail "NaN or Infinity in the JSON"
# the same on two threads
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$LOGS/crate-on-frame.ini" --json \
    --size 1.5x0.728 --threads 2
cmp "$TMP/one.json" "$TMP/out" || fail "what-if differs between 1 and 2 threads"

# --fail-on-overturn, --plot
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --fail-on-overturn --no-what-if
expect_rc 1 "--fail-on-overturn"
# --accuracy reaches the safety-factor and what-if runs: the cushion has
# no measured table, so its row says so instead of running at defaults.
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --cushion-omega 30 \
    --accuracy 1e-6
expect_rc 0 "--accuracy"
grep -q "cushion *n/a: accuracy 1e-06 rad.*no measured table" "$TMP/out" || {
    show
    fail "--accuracy did not reach the cushion what-if"
}
if command -v gnuplot >/dev/null 2>&1; then
    run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --no-what-if --plot "$TMP/f.png"
    expect_rc 0 "--plot"
    head -c 8 "$TMP/f.png" | od -An -tx1 | grep -q '89 50 4e 47' || fail "--plot: not a PNG"
fi
echo "ok"
