#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""run.py - the bad-input catalogue: runs every case of MANIFEST through the
swaywatch command and checks what it promises.

    run.py SWAYWATCH SOURCE_DIR WORK_DIR [--feed SW_ACCEL_FEED] [NAME_PREFIX...]

MANIFEST has one case per line, fields separated by '|':

    name | arguments | exit code | stderr contains | counts

Arguments are split like a shell would split them, after replacing {d}
(this folder), {src} (the source tree), {gen} (inputs made at test time,
see make_inputs(); lcm-logger files need --feed) and {tmp} (a scratch
folder of the case).  Counts are
"key=value" pairs checked against the JSON summary; a key may be a dotted
path into it ("packages.0.faults=0"); stderr_lines counts lines on stderr.

Besides what a case states, every run must:
  - end with its exit code, never by a signal, with nothing from a
    sanitizer on stderr;
  - put "swaywatch: " in front of every line on stderr;
  - for replay and simulate ending in 0 or 1 (the driver adds --json,
    --out, --events and, unless given, --settle 0): write strict JSON
    without NaN or Infinity, and --out / --events files whose every number
    is finite; one state row per accepted sample and package; as many
    "FILE:LINE: reason" lines (plus "... N more") as rejected samples; and
    samples_read = accepted + samples_rejected.
"""
import csv
import json
import math
import os
import random
import re
import shlex
import subprocess
import sys

TIMEOUT = 120  # s per run; the 10 MB line and an hour-long gap take < 5 s


# lcm-logger files: name -> sw_accel_feed arguments.  The feed is seeded,
# so the counts in MANIFEST are exact.
LCM_LOGS = {
    "clean": ["--count", "2000"],
    "all-kinds": ["--count", "2000", "--garbage", "100"],
    "only-garbage": ["--count", "0", "--empty", "50"],
}
for _k in ("fingerprint", "other_type", "truncated", "empty", "trailing", "oversized",
           "nonfinite", "implausible", "duplicate", "out_of_order", "past", "future"):
    LCM_LOGS[_k] = ["--count", "200", "--garbage", "1000", "--kinds", _k]


def make_inputs(gen, feed):
    """Inputs too big (or too binary) to keep in the repository."""
    os.makedirs(gen, exist_ok=True)
    if feed:
        for name, args in LCM_LOGS.items():
            subprocess.run([feed, "log", os.path.join(gen, "lcm-%s.lcmlog" % name)] + args,
                           check=True, stdout=subprocess.DEVNULL)
    rows = "".join("%.3f,%.3f\n" % (i * 1e-3, -0.5 * (i % 7)) for i in range(200))
    rows2 = "".join("%.3f,%.3f\n" % (0.2 + i * 1e-3, 0.1) for i in range(200))
    # A 10 MB line in the middle of a good log: rejected, the rest read.
    with open(os.path.join(gen, "long-line.csv"), "w") as f:
        f.write("time,accel\n" + rows + "0.1999," + "7" * (10 << 20) + "\n" + rows2)
    # Thousands of columns: the two wanted ones are read, the rest ignored.
    with open(os.path.join(gen, "wide.csv"), "w") as f:
        f.write(",".join(["time", "accel"] + ["c%d" % i for i in range(5000)]) + "\n")
        for i in range(100):
            f.write("%.3f,%.3f," % (i * 1e-3, 0.2) + ",".join(["1.5"] * 5000) + "\n")
    # Binary garbage, reproducible.
    rnd = random.Random(7)
    with open(os.path.join(gen, "garbage.bin"), "wb") as f:
        f.write(bytes(rnd.randrange(256) for _ in range(65536)))
    # A "scene file" larger than the 1 MiB the command reads.
    with open(os.path.join(gen, "huge.ini"), "w") as f:
        f.write("[package]\nname = big\n" + ("# padding\n" * 120000))


def load_manifest(path):
    cases = []
    with open(path) as f:
        for num, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            parts = [p.strip() for p in line.split("|")]
            if len(parts) != 5:
                sys.exit("MANIFEST:%d: expected 5 fields separated by '|'" % num)
            name, args, code, err, counts = parts
            want = {}
            for kv in counts.split():
                k, _, v = kv.partition("=")
                want[k] = int(v)
            cases.append(dict(line=num, name=name, args=args, exit=int(code), err=err,
                              counts=want))
    return cases


def strict_json(text):
    def refuse(tok):
        raise ValueError("non-finite number %s in JSON" % tok)
    return json.loads(text, parse_constant=refuse)


def dig(obj, path):
    for k in path.split("."):
        obj = obj[int(k)] if isinstance(obj, list) else obj[k]
    return obj


def check_numbers_csv(path, text_cols, problems):
    """Every field but the text columns is a finite number; returns rows."""
    rows = []
    with open(path, newline="") as f:
        r = csv.reader(f)
        header = next(r, None)
        if header is None:
            problems.append("%s: no header" % os.path.basename(path))
            return rows
        for n, row in enumerate(r, 2):
            if len(row) != len(header):
                problems.append("%s:%d: %d fields, header has %d"
                                % (os.path.basename(path), n, len(row), len(header)))
                continue
            for i, v in enumerate(row):
                if header[i] in text_cols:
                    continue
                try:
                    ok = math.isfinite(float(v))
                except ValueError:
                    ok = False
                if not ok:
                    problems.append("%s:%d: %s = %r is not a finite number"
                                    % (os.path.basename(path), n, header[i], v))
            rows.append(dict(zip(header, row)))
    return rows


def run_case(sw, case, subst, tmp):
    problems = []
    os.makedirs(tmp, exist_ok=True)
    s = dict(subst, tmp=tmp)
    args = [a.format(**s) for a in shlex.split(case["args"])]
    cmd = args[0] if args else ""
    full = cmd in ("replay", "simulate") and case["exit"] in (0, 1)
    out_csv = os.path.join(tmp, "state.csv")
    ev_csv = os.path.join(tmp, "events.csv")
    if full:
        args += ["--json", "--out", out_csv, "--events", ev_csv]
        if cmd == "replay" and "--settle" not in args:
            args += ["--settle", "0"]
    try:
        p = subprocess.run([sw] + args, capture_output=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return ["no answer within %d s" % TIMEOUT]
    err = p.stderr.decode("utf-8", "replace")
    if p.returncode < 0:
        problems.append("killed by signal %d" % -p.returncode)
    elif p.returncode != case["exit"]:
        problems.append("exit status %d, expected %d" % (p.returncode, case["exit"]))
    if re.search(r"AddressSanitizer|LeakSanitizer|runtime error:|Segmentation", err):
        problems.append("sanitizer or crash report on stderr")
    if case["err"] and case["err"] not in err:
        problems.append("stderr lacks %r" % case["err"])
    for line in err.splitlines():
        if not line.startswith("swaywatch: ") and not line.startswith(" "):
            problems.append("stderr line without the prefix: %r" % line[:100])
            break

    want = dict(case["counts"])
    if "stderr_lines" in want:
        got = len(err.splitlines())
        if got != want["stderr_lines"]:
            problems.append("%d lines on stderr, expected %d" % (got, want["stderr_lines"]))
        del want["stderr_lines"]

    j = None
    if full:
        try:
            j = strict_json(p.stdout.decode("utf-8"))
        except ValueError as e:
            problems.append("stdout is not strict JSON: %s" % e)
    elif want:
        try:
            j = strict_json(p.stdout.decode("utf-8"))
        except ValueError as e:
            problems.append("stdout is not strict JSON: %s" % e)
    if j is not None:
        for k, v in want.items():
            try:
                got = (j["samples_read"] - j["samples_rejected"] if k == "accepted"
                       else dig(j, k))
            except (KeyError, IndexError, TypeError):
                problems.append("JSON has no %s" % k)
                continue
            if got != v:
                problems.append("%s = %s, expected %d" % (k, got, v))
    if full and j is not None:
        read, rej = j.get("samples_read"), j.get("samples_rejected")
        accepted = read - rej if cmd == "replay" else None
        if cmd == "replay" and not (0 <= rej <= read):
            problems.append("samples_rejected %s not within 0..samples_read %s" % (rej, read))
        states = check_numbers_csv(out_csv, {"package", "phase"}, problems)
        check_numbers_csv(ev_csv, {"package", "event"}, problems)
        for k, pk in enumerate(j.get("packages", [])):
            rows = sum(1 for r in states if r["package"] == pk["name"])
            if accepted is not None and rows != accepted:
                problems.append("package %s: %d state rows, %d samples accepted"
                                % (pk["name"], rows, accepted))
            if pk.get("samples_read") != read or pk.get("samples_rejected") != rej:
                problems.append("package %s: counts differ from the top level" % pk["name"])
        lcmlog = any(a.endswith(".lcmlog") for a in args)
        if cmd == "replay" and not lcmlog and "--strict" not in args:
            listed = len(re.findall(r"^swaywatch: .*:\d+: (?!note: )", err, re.M))
            more = re.search(r"\.\.\. (\d+) more rejected rows", err)
            listed += int(more.group(1)) if more else 0
            if listed != rej:
                problems.append("%d rejected rows reported on stderr, JSON says %d"
                                % (listed, rej))
    return problems


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    sw, src, work = sys.argv[1:4]
    rest = sys.argv[4:]
    feed = None
    if len(rest) >= 2 and rest[0] == "--feed":
        feed, rest = rest[1], rest[2:]
    prefixes = rest
    here = os.path.dirname(os.path.abspath(__file__))
    gen = os.path.join(work, "gen")
    make_inputs(gen, feed)
    subst = dict(d=here, src=src, gen=gen)
    cases = [c for c in load_manifest(os.path.join(here, "MANIFEST"))
             if not prefixes or any(c["name"].startswith(p) for p in prefixes)]
    failed = 0
    for c in cases:
        problems = run_case(sw, c, subst, os.path.join(work, "cases", c["name"]))
        if problems:
            failed += 1
            print("FAIL %s (MANIFEST:%d)" % (c["name"], c["line"]))
            for pr in problems[:10]:
                print("     " + pr)
        else:
            print("ok   %s" % c["name"])
    print("%d cases, %d failed" % (len(cases), failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
