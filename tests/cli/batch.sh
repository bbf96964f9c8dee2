# SPDX-License-Identifier: GPL-3.0-or-later
# batch.sh - "swaywatch batch": usage, the manifest's errors stopping the
# batch before any log runs, and a batch of twenty logs of different
# lengths (six that fail) checked against 'swaywatch replay' run on each
# log alone: the same fields, the same exit code and messages for the
# failures, in the manifest's order, the same bytes on 1, 2 and 3 threads,
# the CSV table the same as the records.
. "$(dirname "$0")/lib.sh"
CRATE=$SRC/sample_logs/crate.ini
FRAME=$SRC/sample_logs/crate-on-frame.ini
B=$TMP/b
python3 "$SRC/tests/cli/mkbatch.py" "$B" "$SRC/sample_logs"
M=$B/manifest.txt

run "$SW" batch --help
expect_rc 0 "batch --help"
[ ! -s "$TMP/err" ] || fail "batch --help wrote to stderr"
grep -q '^usage: swaywatch batch' "$TMP/out" || fail "batch --help: no usage line"
for opt in --manifest --job --threads --out --csv --progress --quiet --scene --accel-unit \
    --settle --max-accel --fail-on-overturn 'Exit codes: 0' '4 some logs'; do
    grep -q -- "$opt" "$TMP/out" || fail "batch --help: $opt not listed"
done
run "$SW" help batch
expect_rc 0 "help batch"

# ---- what stops a batch before any log runs: exit 2 (3 for files) ----
run "$SW" batch --scene "$CRATE"
expect_rc 2 "no logs"
expect_err "no logs" "no logs"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/none.txt"
expect_rc 3 "missing manifest"
run "$SW" batch --scene "$CRATE" --job nonesuch "$B/a01.csv"
expect_rc 2 "--job nonesuch"
expect_err "--job: expected replay or forensics, got 'nonesuch'" "--job nonesuch"
run "$SW" batch --scene "$CRATE" -
expect_rc 2 "standard input as a log"
printf '%s/a01.csv\n%s/a02.csv "--scene\n' "$B" "$B" >"$TMP/m1"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/m1" -o "$TMP/none.jsonl"
expect_rc 2 "quote not closed"
expect_err "$TMP/m1:2: a double quote is not closed" "quote not closed"
[ ! -e "$TMP/none.jsonl" ] || fail "a bad manifest created the output"
printf '%s/a01.csv\n\n%s/a02.csv --threads 2\n' "$B" "$B" >"$TMP/m2"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/m2"
expect_rc 2 "a batch option in a line"
expect_err "$TMP/m2:3: batch: unknown option '--threads'" "a batch option in a line"
[ ! -s "$TMP/out" ] || fail "a bad manifest line: records written"
printf -- '--scene %s %s/a01.csv\n' "$CRATE" "$B" >"$TMP/m3"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/m3"
expect_rc 2 "a line that begins with an option"
expect_err "$TMP/m3:1: a line begins with the log" "a line that begins with an option"
printf '%s/a01.csv --dt -1\n' "$B" >"$TMP/m4"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/m4"
expect_rc 2 "a bad value in a line"
expect_err "$TMP/m4:1: --dt: expected a positive number" "a bad value in a line"
printf '%s/a01.csv --scene %s/none.ini\n' "$B" "$TMP" >"$TMP/m5"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/m5"
expect_rc 3 "a line's missing scene"
expect_err "$TMP/m5:1: $TMP/none.ini: cannot open" "a line's missing scene"
run "$SW" batch --scene "$TMP/none.ini" "$B/a01.csv"
expect_rc 3 "a missing scene"
run "$SW" batch "$B/a01.csv"
expect_rc 2 "no --scene"
run "$SW" batch --scene "$CRATE" "$B/a01.csv" -o "$TMP/x" --csv "$TMP/x"
expect_rc 2 "--out and --csv the same file"
run "$SW" batch --scene "$CRATE" "$B/a01.csv" --csv -
expect_rc 2 "--csv - with the records on standard output"
run "$SW" batch --scene "$CRATE" "$B/a01.csv" -o "$B/a01.csv"
expect_rc 2 "--out is a log"
[ -s "$B/a01.csv" ] || fail "--out truncated a log"

# ---- the batch, on 1, 2 and 3 threads: the same bytes ----
for n in 1 2 3; do
    run "$SW" batch --scene "$CRATE" --scene "$FRAME" --manifest "$M" --threads $n \
        -o "$TMP/r$n.jsonl" --csv "$TMP/r$n.csv" --no-progress
    expect_rc 4 "a batch with failing logs, --threads $n"
    expect_prefixed_err "batch --threads $n"
done
for n in 2 3; do
    cmp "$TMP/r1.jsonl" "$TMP/r$n.jsonl" || fail "records differ between 1 and $n threads"
    cmp "$TMP/r1.csv" "$TMP/r$n.csv" || fail "CSV differs between 1 and $n threads"
done
expect_err "batch: 20 logs: 14 done, 6 failed; 33 records to $TMP/r3.jsonl" "the summary"
# the messages of the logs, once each, in the manifest's order
grep -n 'b/missing.csv: cannot open\|b/empty.csv: no usable' "$TMP/err" | cut -d: -f1 >"$TMP/at"
[ "$(wc -l <"$TMP/at")" -eq 2 ] || { show; fail "messages of the failing logs"; }
sort -n -c "$TMP/at" 2>/dev/null || fail "messages out of order"

# records on standard output when --out is not given; -q: nothing on stderr
run "$SW" batch --scene "$CRATE" --scene "$FRAME" --manifest "$M" -q
expect_rc 4 "records on standard output"
[ ! -s "$TMP/err" ] || { show; fail "-q: batch wrote to stderr"; }
cmp "$TMP/out" "$TMP/r1.jsonl" || fail "records on standard output differ from --out"

# Each log run alone by replay, with the batch's options and the line's
# (split by Python's shlex, not by swaywatch): the same fields, exit code
# and messages.
python3 - "$SW" "$M" "$TMP/r1.jsonl" "$TMP/r1.csv" "$CRATE" "$FRAME" <<'PY' || fail "records against replay"
import csv, json, shlex, subprocess, sys
sw, man, recs, table, crate, frame = sys.argv[1:]
lines = []
for no, text in enumerate(open(man), 1):
    words = shlex.split(text, comments=True)
    if words:
        lines.append((no, words[0], words[1:]))
records = [json.loads(l) for l in open(recs)]
rows = list(csv.DictReader(open(table)))
assert len(rows) == len(records), (len(rows), len(records))
header = open(table).readline().strip().split(",")
assert all(None not in r and len(r) == len(header) for r in rows), "a row of another width"
at = 0
for index, (no, log, opts) in enumerate(lines, 1):
    scenes = ["--scene", crate, "--scene", frame] if "--scene" not in opts else []
    p = subprocess.run([sw, "replay", log, "--json"] + scenes + opts,
                       capture_output=True, text=True)
    mine = []
    while at < len(records) and records[at]["index"] == index:
        mine.append((records[at], rows[at]))
        at += 1
    assert mine, ("no record", index, log)
    for rec, row in mine:
        assert rec["log"] == log and rec["line"] == no and rec["job"] == "replay", rec
        assert row["log"] == log and row["line"] == str(no) and row["index"] == str(index)
    if p.returncode not in (0, 1):
        (rec, row), = mine
        assert rec["status"] == "error" and rec["exit"] == p.returncode, (rec, p.returncode)
        q = subprocess.run([sw, "replay", log, "-q"] + scenes + opts, capture_output=True,
                           text=True)
        said = [l[len("swaywatch: "):] for l in q.stderr.splitlines()]
        assert rec["messages"] == said, (rec["messages"], said)
        assert row["status"] == "error" and row["messages"] == " | ".join(said), row
        continue
    j = json.loads(p.stdout)
    assert len(mine) == len(j["packages"]), (log, len(mine))
    for (rec, row), pkg in zip(mine, j["packages"]):
        # an incomplete verdict is the record's status (verdict.sh makes one)
        status = "incomplete" if pkg["verdict"] == "incomplete" else "ok"
        assert rec["status"] == status and row["status"] == status, rec
        for k, v in pkg.items():
            assert rec[k] == v, (log, k, rec[k], v)
        assert rec["input"] == j["input"] and rec["settle"] == j["settle"], log
        said = [l[len("swaywatch: "):] for l in p.stderr.splitlines()
                if "warning" in l or "forced" in l]
        assert all(m in rec["messages"] for m in said), (rec["messages"], said)
        # the table holds the same numbers
        assert row["package"] == pkg["name"] and row["model"] == pkg["model"], row
        assert row["overturned"] == str(int(pkg["overturned"])), row
        assert row["verdict"] == pkg["verdict"], (row["verdict"], pkg["verdict"])
        for k in ("overturn_time", "tip_time", "uplift_time", "max_abs_theta", "min_margin",
                  "dt", "min_reserve_g", "min_reserve_time", "rest_reserve_g"):
            want = pkg[k]
            assert (row[k] == "" if want is None else abs(float(row[k]) - want) <= 1e-9 * abs(want)), (k, row[k], want)
        for k in ("impacts", "uplifts", "samples_read", "samples_rejected", "steps"):
            assert int(row[k]) == pkg[k], (k, row[k], pkg[k])
        assert abs(float(row["duration"]) - j["input"]["duration"]) < 1e-9, row
assert at == len(records), "records beyond the manifest"
# the line with its own scene has its package only; the one in g and ms
# gives what the same drive in m/s^2 and s gives
own = [r for r in records if r["log"].endswith("a05.csv") and r["line"] is not None]
assert sorted(r["name"] for r in own) == ["crate-A", "crate-A-on-cushion", "crate-A-on-frame"], own
g = {r["name"]: r for r in records if r["log"].endswith("g-units.csv")}
si = {r["name"]: r for r in records if r["log"].endswith("a12.csv")}
for name in g:
    assert g[name]["overturned"] == si[name]["overturned"], name
    assert abs(g[name]["max_theta_ratio"] - si[name]["max_theta_ratio"]) < 1e-3 * si[name]["max_theta_ratio"] + 1e-6, name
assert sum(r["status"] == "error" for r in records) == 6
assert any(r["overturned"] for r in records if r["status"] == "ok"), "nothing overturned"
assert all(r["status"] in ("ok", "incomplete", "error") for r in records), records
PY

# Operands come before the manifest's lines; only good logs: exit 0, or
# 1 with --fail-on-overturn when one overturned.
printf '%s/a01.csv\n' "$B" >"$TMP/m6"
run "$SW" batch --scene "$FRAME" "$B/a04.csv" --manifest "$TMP/m6" "$B/a06.csv"
expect_rc 0 "good logs"
python3 - "$TMP/out" "$B" <<'PY' || fail "operands, then the manifest"
import json, sys
logs = [json.loads(l)["log"] for l in open(sys.argv[1])]
b = sys.argv[2]
assert logs == [b + "/a04.csv", b + "/a06.csv", b + "/a01.csv"], logs
PY
run "$SW" batch --scene "$FRAME" "$B/a04.csv" "$B/a06.csv" --fail-on-overturn
grep -q '"overturned": true' "$TMP/out" || { show; fail "a06 on the frame does not overturn"; }
expect_rc 1 "--fail-on-overturn"
run "$SW" batch --scene "$CRATE" "$B/a04.csv" "$B/a01.csv" --fail-on-overturn
expect_rc 0 "--fail-on-overturn, nothing overturned"

# --job forensics: a record per log and package with forensics' JSON for
# it, the same as "swaywatch forensics --json" of each log on its own, and
# a CSV row of the answer; the threads give the same records.
LOGS=$SRC/sample_logs
for t in 1 2; do
    run "$SW" batch --job forensics --scene "$CRATE" --scene "$LOGS/crate-on-frame.ini" \
        --frame-omega 1Hz --cushion-omega 8Hz --threads $t --csv "$TMP/f$t.csv" \
        "$LOGS/hard-stop-overturn.csv" "$LOGS/braking-pothole.csv"
    expect_rc 0 "batch --job forensics --threads $t"
    cp "$TMP/out" "$TMP/f$t.jsonl"
done
cmp "$TMP/f1.jsonl" "$TMP/f2.jsonl" || fail "batch forensics differs between 1 and 2 threads"
for log in hard-stop-overturn braking-pothole; do
    run "$SW" forensics "$LOGS/$log.csv" --scene "$CRATE" --scene "$LOGS/crate-on-frame.ini" \
        --frame-omega 1Hz --cushion-omega 8Hz --json
    expect_rc 0 "forensics $log"
    cp "$TMP/out" "$TMP/$log.json"
done
python3 - "$TMP/f1.jsonl" "$TMP/f1.csv" "$TMP/hard-stop-overturn.json" "$TMP/braking-pothole.json" <<'PY' || fail "batch forensics against forensics"
import csv, json, sys
recs = [json.loads(l) for l in open(sys.argv[1])]
rows = list(csv.DictReader(open(sys.argv[2])))
alone = {"hard-stop-overturn": json.load(open(sys.argv[3])), "braking-pothole": json.load(open(sys.argv[4]))}
assert len(recs) == len(rows) == 4, (len(recs), len(rows))
for rec, row in zip(recs, rows):
    assert rec["job"] == "forensics" and rec["status"] == "ok", rec
    name = rec["log"].rsplit("/", 1)[1][:-4]
    pk = [p for p in alone[name]["packages"] if p["name"] == rec["name"]][0]
    for k in ("verdict", "overturned", "min_margin", "min_reserve_g", "safety_factor", "saved_by", "what_if"):
        assert rec[k] == pk[k], (name, rec["name"], k)
    assert row["package"] == rec["name"] and row["verdict"] == rec["verdict"]
    assert float(row["factor"]) == rec["safety_factor"]["factor"]
    assert float(row["factor_safe"]) == rec["safety_factor"]["factor_safe"]
# the frame overturns on the braking the bare crate survives
v = {(r["log"].rsplit("/", 1)[1], r["name"]): r["verdict"] for r in recs}
assert v[("braking-pothole.csv", "crate-A")] == "upright"
assert v[("braking-pothole.csv", "crate-A-on-frame")] == "overturned"
PY

# A large manifest (generated: 20,000 lines over 1,000 sets of options, in
# a scrambled order) is planned whole: each set parsed once, at its first
# line, and a bad option on the last line stops the batch before any log
# runs.  Lines that share options, and lines that have none, share a set:
# a small batch of the same shape gives each record its own line's scene.
# (The work of the grouping is counted in test_keyset.)
python3 - "$TMP/big.txt" "$B/a01.csv" <<'PY'
import sys
with open(sys.argv[1], "w") as f:
    for i in range(20000):
        f.write("%s --set package.mass=%d\n" % (sys.argv[2], 100 + (i * 7919) % 1000))
    f.write("%s --no-such-option\n" % sys.argv[2])
PY
run "$SW" batch --scene "$CRATE" --manifest "$TMP/big.txt" -o "$TMP/big.jsonl"
expect_rc 2 "a large manifest with a bad last line"
expect_err "$TMP/big.txt:20001: batch: unknown option '--no-such-option'" "large manifest"
[ ! -e "$TMP/big.jsonl" ] || fail "a large manifest with a bad last line: records written"
sed 's/name *= *.*/name = other/' "$CRATE" >"$TMP/other.ini"
printf '%s\n%s --scene %s\n%s\n%s --scene %s\n' "$B/a01.csv" "$B/a01.csv" "$TMP/other.ini" \
    "$B/a01.csv" "$B/a01.csv" "$TMP/other.ini" >"$TMP/mix.txt"
run "$SW" batch --scene "$CRATE" --manifest "$TMP/mix.txt" -o "$TMP/mix.jsonl" -q
expect_rc 0 "lines sharing sets"
python3 - "$TMP/mix.jsonl" <<'PY' || fail "lines sharing sets: a record has another line's scene"
import json, sys
names = [json.loads(l)["name"] for l in open(sys.argv[1])]
assert names == ["crate-A", "other", "crate-A", "other"], names
PY

# --progress: the logs done, on stderr
run "$SW" batch --scene "$CRATE" "$B/a04.csv" "$B/a01.csv" --progress -o "$TMP/p.jsonl"
expect_rc 0 "--progress"
grep -q '100% (2/2 logs)' "$TMP/err" || { show; fail "--progress"; }
exit 0
