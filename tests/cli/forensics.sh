# SPDX-License-Identifier: GPL-3.0-or-later
# forensics.sh - "swaywatch forensics": the answer, the safety factor as a
# bracket (<= 1 for a log that overturned, > 1 for one that did not; a
# direct replay of the log scaled by its lower end stays upright and by its
# upper end overturns), two scenes at once, the catalogue's what-if table,
# frequencies in Hz and rad/s, JSON, thread counts, CSV against
# lcm-logger files, and the figure.
. "$(dirname "$0")/lib.sh"
LOGS=$SRC/sample_logs
CRATE=$LOGS/crate.ini

run "$SW" forensics --help
expect_rc 0 "forensics --help"
[ ! -s "$TMP/err" ] || fail "forensics --help wrote to stderr"
for opt in --scene --settle --frame-mass --frame-omega --frame-zeta --cushion-omega \
    --cushion-zeta --size --plot --report --json --threads --time-col --accel-unit \
    --accel-channel 'Exit codes: 0 ok'; do
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
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --frame-omega 2kHz
expect_rc 2 "bad --frame-omega unit"
expect_err "expected Hz or rad/s" "bad --frame-omega unit"

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

# check LOG OVERTURNED: the safety factor is on the right side of 1, and a
# direct replay of the log scaled by the lower end of its bracket stays
# upright, by the upper end overturns (both ends were run by the search).
check() {
    run "$SW" forensics "$1" --scene "$CRATE" --json --no-what-if
    expect_rc 0 "forensics $1"
    cp "$TMP/out" "$TMP/f.json"
    json_check "$TMP/f.json" "j['replay']['packages'][0]['overturned'] == $2 and j['packages'][0]['safety_factor']['overturned'] == $2"
    if [ "$2" = True ]; then
        json_check "$TMP/f.json" 'j["packages"][0]["safety_factor"]["factor"] <= 1'
    else
        json_check "$TMP/f.json" 'j["packages"][0]["safety_factor"]["factor"] > 1'
    fi
    json_check "$TMP/f.json" 'j["packages"][0]["safety_factor"]["bracket"] == [j["packages"][0]["safety_factor"]["factor_safe"], j["packages"][0]["safety_factor"]["factor"]]'
    for end in 0 1; do
        f=$(python3 -c 'import json,sys; print(repr(json.load(open(sys.argv[1]))["packages"][0]["safety_factor"]["bracket"][int(sys.argv[2])]))' "$TMP/f.json" $end)
        scale "$1" "$f" "$TMP/s.csv"
        run "$SW" replay "$TMP/s.csv" --scene "$CRATE" --json
        expect_rc 0 "replay x$f"
        cp "$TMP/out" "$TMP/r$end.json"
    done
    json_check "$TMP/r0.json" 'not j["packages"][0]["overturned"]'
    json_check "$TMP/r1.json" 'j["packages"][0]["overturned"]'
}
check "$LOGS/hard-stop-overturn.csv" True
check "$LOGS/braking-pothole.csv" False

# Two scenes: each its own answer, safety factor and what-if rows; the
# bare crate's factor is the one it has alone.
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" --scene "$LOGS/crate-on-frame.ini" \
    --json --size 2.4x0.8
expect_rc 0 "two scenes"
cp "$TMP/out" "$TMP/two.json"
json_check "$TMP/two.json" '[p["name"] for p in j["packages"]] == ["crate-A", "crate-A-on-frame"]'
json_check "$TMP/two.json" 'not j["packages"][0]["overturned"] and j["packages"][1]["overturned"]'
json_check "$TMP/two.json" 'j["packages"][0]["safety_factor"]["factor"] > 1 > j["packages"][1]["safety_factor"]["factor"]'
json_check "$TMP/two.json" 'all(c["case"] == "as given" for c in (p["what_if"][0] for p in j["packages"]))'
json_check "$TMP/two.json" 'j["packages"][1]["what_if"][1]["case"] == "bed" and j["packages"][1]["what_if"][1]["model"] == "bare"'
# the frame's "bed" row is the bare crate: the same factor as crate-A's own
json_check "$TMP/two.json" 'j["packages"][1]["what_if"][1]["safety_factor"]["bracket"] == j["packages"][0]["safety_factor"]["bracket"]'
json_check "$TMP/two.json" 'j["packages"][1]["saved_by"] and "bed" in j["packages"][1]["saved_by"]'
# the catalogue: two frames and two cushions, in Hz, with what they stand for
json_check "$TMP/two.json" 'sum(1 for c in j["packages"][0]["what_if"] if "stands_for" in c) == 4'
json_check "$TMP/two.json" 'any("1 Hz" in c.get("support", "") for c in j["packages"][0]["what_if"])'
json_check "$TMP/two.json" '[c["case"] for c in j["packages"][0]["what_if"]][-1] == "size 2.4x0.8 m"'
grep -Eqi 'nan|infinity' "$TMP/two.json" && fail "NaN or Infinity in the JSON"
# each package's smallest reserve is the one replay finds for it
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$CRATE" --scene "$LOGS/crate-on-frame.ini" --json
expect_rc 0 "replay of the two scenes"
cp "$TMP/out" "$TMP/two-replay.json"
python3 - "$TMP/two.json" "$TMP/two-replay.json" <<'PY' || fail "forensics' reserve differs from replay's"
import json, sys
f, r = (json.load(open(p)) for p in sys.argv[1:])
for pf, pr in zip(f["packages"], r["packages"]):
    assert pr["min_reserve_g"] is not None, pr  # 0 for the frame: it overturned
    assert pf["min_reserve_g"] == pr["min_reserve_g"], (pf["min_reserve_g"], pr["min_reserve_g"])
    assert pf["min_reserve_time"] == pr["min_reserve_time"]
    # the row "as given" is the package's own
    w = pf["what_if"][0]
    assert w["min_reserve_g"] == pf["min_reserve_g"] and w["min_reserve_exact"], w
PY
# every what-if row has its smallest reserve: 0 where it overturned; the
# frame's "bed" row is the bare crate, whose exhaustive minimum replay
# found (the pruned search must find the very same state)
python3 - "$TMP/two.json" <<'PY' || fail "what-if reserves"
import json, sys
j = json.load(open(sys.argv[1]))
for p in j["packages"]:
    for c in p["what_if"]:
        if not c["available"]:
            continue
        assert c["min_reserve_g"] is not None, c
        assert c["min_reserve_lower_g"] <= c["min_reserve_g"], c
        if c["overturned"]:
            assert c["min_reserve_g"] == 0 and c["min_reserve_exact"], c
        assert c["reserve_evaluations"] <= 400 or c["as_given"], c
bed = j["packages"][1]["what_if"][1]
crate = j["packages"][0]
assert bed["min_reserve_exact"], bed
assert bed["min_reserve_g"] == crate["min_reserve_g"], (bed, crate["min_reserve_g"])
assert bed["min_reserve_time"] == crate["min_reserve_time"], (bed, crate["min_reserve_time"])
PY
# a budget of one evaluation: a bracket that holds the exact value
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" --json --reserve-evals 1 \
    --frame-omega 5Hz --cushion-omega 60
expect_rc 0 "--reserve-evals 1"
cp "$TMP/out" "$TMP/ev1.json"
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" --json --reserve-evals 0 \
    --frame-omega 5Hz --cushion-omega 60
expect_rc 0 "--reserve-evals 0"
cp "$TMP/out" "$TMP/ev0.json"
python3 - "$TMP/ev1.json" "$TMP/ev0.json" <<'PY' || fail "--reserve-evals bracket"
import json, sys
a, b = (json.load(open(p))["packages"][0]["what_if"] for p in sys.argv[1:])
for ca, cb in zip(a[1:], b[1:]):
    assert cb["min_reserve_exact"], cb
    assert ca["reserve_evaluations"] <= 1, ca
    assert ca["min_reserve_lower_g"] <= cb["min_reserve_g"] <= ca["min_reserve_g"], (ca, cb)
assert any(not c["min_reserve_exact"] for c in a[1:]), "one evaluation cannot prove every minimum"
PY

# Hz and rad/s name the same frame: 1Hz = 6.283185307179586 rad/s.
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" --frame-omega 1Hz --json \
    --cushion-omega 60
cp "$TMP/out" "$TMP/hz.json"
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" \
    --frame-omega 6.283185307179586rad/s --json --cushion-omega 60
cp "$TMP/out" "$TMP/rad.json"
python3 - "$TMP/hz.json" "$TMP/rad.json" <<'PY' || fail "--frame-omega 1Hz differs from 2 pi rad/s"
import json, sys
a, b = (json.load(open(p))["packages"][0]["what_if"] for p in sys.argv[1:])
fa = [c for c in a if c["case"] == "frame"][0]
fb = [c for c in b if c["case"] == "frame"][0]
assert fa["safety_factor"]["bracket"] == fb["safety_factor"]["bracket"], (fa, fb)
assert not any("stands_for" in c for c in a), "the user's supports replace the catalogue's"
PY

# The human report: replay's summary, the factor, the what-if table; the
# cushion row is computed, or says why not (a build without the cushion
# model), never an error.
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" --frame-omega 3 \
    --cushion-omega 60 --size 2.4x0.8
expect_rc 0 "what-if"
for want in 'crate-A (2x0.728 m, 1000 kg, on the bed): stayed upright' 'safety factor [' \
    'It stayed upright' 'package crate-A: bare model' 'minimum margin' 'what if' 'as given' \
    'frame ' 'cushion ' 'size 2.4x0.8 m' 'How this was found'; do
    grep -qF "$want" "$TMP/out" || { show; fail "report lacks '$want'"; }
done
cushion=$(grep '^  cushion ' "$TMP/out")
case "$cushion" in
*"n/a: cushion model not in this build"*) ;;
*upright* | *OVERTURNED*) ;;
*) show; fail "cushion row: $cushion" ;;
esac
# The answer comes first, the method after; -q keeps the answer alone.
answer_line=$(grep -n 'safety factor \[' "$TMP/out" | head -1 | cut -d: -f1)
method_line=$(grep -n 'How this was found' "$TMP/out" | cut -d: -f1)
[ "$answer_line" -lt "$method_line" ] || fail "the method comes before the answer"
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$CRATE" -q --frame-omega 3 \
    --cushion-omega 60 --size 2.4x0.8
expect_rc 0 "-q"
grep -qF 'safety factor [' "$TMP/out" || fail "-q hid the answer"
grep -qF 'what if' "$TMP/out" || fail "-q hid the what-if table"
grep -qF 'How this was found' "$TMP/out" && fail "-q kept the method"
grep -qF 'package crate-A: bare model' "$TMP/out" && fail "-q kept the replay summary"
[ ! -s "$TMP/err" ] || { show; fail "-q: messages on stderr (a progress line when piped?)"; }

# JSON: one object, the replay summary inside, a row per case
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$LOGS/crate-on-frame.ini" --json \
    --size 1.5x0.728 --threads 1
expect_rc 0 "json"
cp "$TMP/out" "$TMP/one.json"
json_check "$TMP/one.json" '[c["case"] for c in j["packages"][0]["what_if"]][:2] == ["as given", "bed"]'
json_check "$TMP/one.json" 'j["packages"][0]["what_if"][0]["model"] == "frame" and j["packages"][0]["what_if"][1]["model"] == "bare"'
grep -Eqi 'nan|infinity' "$TMP/one.json" && fail "NaN or Infinity in the JSON"
# the same on two threads, and in words: all but the command line
run "$SW" forensics "$LOGS/braking-pothole.csv" --scene "$LOGS/crate-on-frame.ini" --json \
    --size 1.5x0.728 --threads 2
python3 - "$TMP/one.json" "$TMP/out" <<'PY' || fail "the JSON differs between 1 and 2 threads"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
ca, cb = a.pop("command"), b.pop("command")
la, lb = a.pop("command_line"), b.pop("command_line")
assert cb[-2:] == ["--threads", "2"], cb
assert la.endswith(" --threads 1") and lb == la[:-1] + "2", (la, lb)
assert a == b
PY
for n in 1 2; do
    run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --scene "$LOGS/crate-on-frame.ini" \
        --threads $n
    grep -v '^  command ' "$TMP/out" >"$TMP/t$n.txt"
done
cmp "$TMP/t1.txt" "$TMP/t2.txt" || fail "the report differs between 1 and 2 threads"

# The overturn sample as CSV and as an lcm-logger file: the same answer.
if [ -n "${SW_LCM_PYTHON_DIR:-}" ] && "$SW" --help | grep -q monitor; then
    PYTHONPATH=$SW_LCM_PYTHON_DIR python3 "$SRC/docs/examples/csv2lcmlog.py" \
        "$LOGS/hard-stop-overturn.csv" "$TMP/drive.lcmlog" --start-utime 1700000000000000 >/dev/null
    run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --json --cushion-omega 8Hz \
        --frame-omega 1Hz
    expect_rc 0 "forensics of the CSV"
    cp "$TMP/out" "$TMP/csv.json"
    run "$SW" forensics "$TMP/drive.lcmlog" --scene "$CRATE" --json --cushion-omega 8Hz \
        --frame-omega 1Hz
    expect_rc 0 "forensics of the lcm-logger file"
    cp "$TMP/out" "$TMP/lcm.json"
    python3 - "$TMP/csv.json" "$TMP/lcm.json" <<'PY' || fail "CSV and lcm-logger answers differ"
import json, sys
c, l = (json.load(open(p)) for p in sys.argv[1:])
assert c["log"]["source"] == "a CSV log" and l["log"]["source"] == "an lcm-logger file"
assert c["log"]["samples_used"] == l["log"]["samples_used"] == 8001
# lcm-logger's utimes are dates: 1700000000 s is 2023-11-14T22:13:20Z
assert c["log"]["start_utc"] is None
assert l["log"]["start_utc"] == "2023-11-14T22:13:20.000Z", l["log"]["start_utc"]
assert l["log"]["end_utc"] == "2023-11-14T22:13:28.000Z", l["log"]["end_utc"]
assert l["log"]["dates_from"] == "the samples' utime", l["log"]["dates_from"]
assert l["packages"][0]["utc"]["overturn"] == "2023-11-14T22:13:%06.3fZ" % (20 + l["packages"][0]["overturn_time"])
for pc, pl in zip(c["packages"], l["packages"]):
    assert pc["overturned"] and pl["overturned"]
    assert abs(pc["overturn_time"] - pl["overturn_time"]) < 1e-6
    for wc, wl in zip(pc["what_if"], pl["what_if"]):
        assert wc["case"] == wl["case"] and wc["overturned"] == wl["overturned"], (wc, wl)
        bc, bl = wc["safety_factor"]["bracket"], wl["safety_factor"]["bracket"]
        # the times come from utime in microseconds: the same to rounding
        assert all(abs(x - y) <= 2e-3 * y for x, y in zip(bc, bl)), (wc["case"], bc, bl)
PY
    run "$SW" forensics "$TMP/drive.lcmlog" --scene "$CRATE" --time-col 1
    expect_rc 2 "a CSV option on an lcm-logger file"
fi

# The fingerprint: the log's and the scenes' SHA-256 and size as sha256sum
# and wc count them, the command line quoted so that a shell reads it back
# into the same words (a name with a space and a quote), the version with
# the commit git names for the source.
cp "$LOGS/hard-stop-overturn.csv" "$TMP/it's a log.csv"
cp "$CRATE" "$TMP/the crate.ini"
run "$SW" forensics "$TMP/it's a log.csv" --scene "$TMP/the crate.ini" --no-what-if --json \
    --set 'package.name=crate "A"'
expect_rc 0 "forensics of a log with a quote in its name"
cp "$TMP/out" "$TMP/fp.json"
log_sum=$(sha256sum <"$TMP/it's a log.csv" | cut -d' ' -f1)
scene_sum=$(sha256sum <"$TMP/the crate.ini" | cut -d' ' -f1)
log_size=$(wc -c <"$TMP/it's a log.csv" | tr -d ' ')
json_check "$TMP/fp.json" "j['log']['sha256'] == '$log_sum' and j['log']['size'] == $log_size and j['log']['no_digest'] is None"
json_check "$TMP/fp.json" "[s['sha256'] for s in j['scenes']] == ['$scene_sum'] and j['scenes'][0]['path'].endswith('the crate.ini')"
json_check "$TMP/fp.json" '__import__("shlex").split(j["command_line"]) == j["command"] and j["command"][:3] == ["swaywatch", "forensics", j["log"]["name"]]'
# the line, pasted into a shell, runs the same forensics
cmdline=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["command_line"])' "$TMP/fp.json")
run sh -c 'swaywatch() { "$0" "$@"; }; eval "$1"' "$SW" "$cmdline"
expect_rc 0 "the command line run again"
json_check "$TMP/out" "j['packages'][0]['name'] == 'crate \"A\"' and j['log']['sha256'] == '$log_sum'"
json_check "$TMP/fp.json" 'j["build"]["version"] == j["swaywatch"] and j["build"]["text"].startswith(j["swaywatch"] + " (commit ")'
if command -v git >/dev/null 2>&1 && [ "$(git -C "$SRC" rev-parse --show-toplevel 2>/dev/null)" = "$(cd "$SRC" && pwd -P)" ]; then
    # the commit of the build is one of this checkout's history: HEAD, or
    # an ancestor when commits came after the last build
    built=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["build"]["commit"])' "$TMP/fp.json")
    git -C "$SRC" merge-base --is-ancestor "$built" HEAD ||
        fail "the build's commit '$built' is not in the history of HEAD"
    [ ${#built} -eq 40 ] || fail "the build's commit '$built' is not 40 hex digits"
fi
# a pipe cannot be read again: no digest, and why; a file given as standard
# input can
# shellcheck disable=SC2002 # the pipe is the point
cat "$LOGS/hard-stop-overturn.csv" | "$SW" forensics - --scene "$CRATE" --no-what-if --json \
    >"$TMP/pipe.json" 2>/dev/null || fail "forensics of a pipe"
json_check "$TMP/pipe.json" 'j["log"]["sha256"] is None and "pipe" in j["log"]["no_digest"]'
"$SW" forensics - --scene "$CRATE" --no-what-if --json <"$TMP/it's a log.csv" >"$TMP/stdin.json" 2>/dev/null ||
    fail "forensics of standard input"
json_check "$TMP/stdin.json" "j['log']['sha256'] == '$log_sum'"
# the text says it too, after the method
run "$SW" forensics "$TMP/it's a log.csv" --scene "$TMP/the crate.ini" --no-what-if
grep -qF "SHA-256 $log_sum" "$TMP/out" || { show; fail "the text lacks the log's SHA-256"; }

# UTC: a log of epoch times (2024-05-20T12:00:00Z at its start, made here)
# gives its start, end and decisive moments as dates; the same log timed
# from 0 gives none.
python3 - "$LOGS/hard-stop-overturn.csv" "$TMP/epoch.csv" <<'PY'
import sys
with open(sys.argv[1]) as i, open(sys.argv[2], "w") as o:
    o.write("time,accel\n")
    next(i)
    for line in i:
        t, a = line.strip().split(",")
        o.write("%.3f,%s\n" % (1716206400 + float(t), a))
PY
run "$SW" forensics "$TMP/epoch.csv" --scene "$CRATE" --no-what-if --json
expect_rc 0 "forensics of an epoch log"
cp "$TMP/out" "$TMP/epoch.json"
python3 - "$TMP/epoch.json" <<'PY' || fail "UTC times of an epoch log"
import datetime, json, sys
j = json.load(open(sys.argv[1]))
t0 = datetime.datetime(2024, 5, 20, 12, 0, 0, tzinfo=datetime.timezone.utc)
def iso(s):
    return (t0 + datetime.timedelta(milliseconds=round(s * 1000))).strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"
assert j["log"]["start_utc"] == "2024-05-20T12:00:00.000Z", j["log"]["start_utc"]
assert j["log"]["end_utc"] == "2024-05-20T12:00:08.000Z", j["log"]["end_utc"]
assert j["replay"]["input"]["start_absolute"] == j["log"]["start_utc"]
p = j["packages"][0]
r = j["replay"]["packages"][0]
for k, t in (("uplift", r["uplift_time"]), ("tip", r["tip_time"]), ("overturn", r["overturn_time"]),
             ("min_reserve", r["min_reserve_time"])):
    assert t is not None and p["utc"][k] == iso(t), (k, t, p["utc"][k])
PY
run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$CRATE" --no-what-if --json
json_check "$TMP/out" 'j["log"]["start_utc"] is None and j["replay"]["input"]["start_absolute"] is None and set(j["packages"][0]["utc"].values()) == {None}'
# an uptime in seconds is no date (it would read as January 1970)
sed '2,$s/^/1000000+/' "$LOGS/hard-stop-overturn.csv" | python3 -c '
import sys
print(sys.stdin.readline().strip())
for l in sys.stdin:
    t, a = l.strip().split(",")
    print("%.3f,%s" % (eval(t), a))' >"$TMP/uptime.csv"
run "$SW" forensics "$TMP/uptime.csv" --scene "$CRATE" --no-what-if --json
expect_rc 0 "forensics of an uptime log"
json_check "$TMP/out" 'j["log"]["start_utc"] is None and j["packages"][0]["overturned"]'

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
