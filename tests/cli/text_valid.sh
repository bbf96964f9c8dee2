#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# text_valid.sh - text the command writes stays valid whatever bytes a
# name holds.
#  - JSON (replay --json, batch records): log file names and package names
#    with every byte 0x80-0xff, every control byte, ill-formed UTF-8
#    (overlong forms, surrogates, beyond U+10FFFF, cut sequences) and
#    well-formed UTF-8 of every length.  Each output must decode as strict
#    UTF-8 and parse as JSON, and each name must come back as Python's
#    own decoder reads its bytes with errors="replace" (one U+FFFD per
#    maximal subpart: the reference is independent of our code).
#  - CSV (batch --csv, replay --out): text cells that begin with '=', '+',
#    '-', '@', a tab or a carriage return carry a leading "'"; number cells
#    stay numbers (a negative margin is not touched).
. "$(dirname "$0")/lib.sh"

python3 - "$SW" "$SRC" "$TMP" <<'PY' || fail "text written is not valid"
import csv, io, json, os, re, shutil, subprocess, sys

sw, src, tmp = os.path.abspath(sys.argv[1]), sys.argv[2].encode(), sys.argv[3].encode()
work = os.path.join(tmp, b"w")
os.mkdir(work)
log = os.path.join(src, b"sample_logs", b"hard-stop-overturn.csv")
crate = open(os.path.join(src, b"sample_logs", b"crate.ini"), "rb").read()


def named(name):
    """The sample crate's scene with package.name = name."""
    out = re.sub(rb"(?m)^name *=.*$", lambda m: b"name = " + name, crate)
    assert out != crate
    return out

bad = []

# Byte strings for names: every byte >= 0x80 alone, ill-formed and
# well-formed sequences, every control byte (file names only: a scene
# refuses control characters in a name).
high = [bytes([b]) for b in range(0x80, 0x100)]
seqs = [b"\xc0\x80", b"\xc1\xbf", b"\xe0\x80\x80", b"\xe0\x9f\xbf", b"\xed\xa0\x80",
        b"\xed\xbf\xbf", b"\xf0\x80\x80\x80", b"\xf0\x8f\xbf\xbf", b"\xf4\x90\x80\x80",
        b"\xf5\x80\x80\x80", b"\xe2\x82", b"\xe2\x82x", b"\xf0\x9f\x98", b"\xf0\x9f\x98x",
        b"\xc3", b"\xc3\xc3\xa9", b"\xc3\xa9", b"\xe2\x82\xac", b"\xf0\x9f\x98\x80",
        b"\xef\xbf\xbd", b"\xf4\x8f\xbf\xbf", b"\xc2\x80\xc2\x9b\xc2\x9d"]
ctrl = [bytes([b]) for b in list(range(1, 32)) + [127]] + [b'"', b"\\"]


def fname(k, s):
    return b"L%03d_" % k + s + b"_.csv"


# ---- JSON: batch over logs with every such name -----------------------------
names = high + seqs + ctrl
paths = []
for k, s in enumerate(names):
    p = os.path.join(work, fname(k, s))
    shutil.copy(log, p)
    paths.append(p)
scene = os.path.join(work, b"s.ini")
open(scene, "wb").write(named(b"crate\xff\xc3\xa9\xe2\x82"))
r = subprocess.run([sw.encode(), b"batch", b"-s", scene, b"--threads", b"2", b"-q",
                    b"-o", os.path.join(work, b"b.jsonl"), b"--csv", os.path.join(work, b"b.csv")]
                   + paths, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
if r.returncode != 0:
    bad.append("batch: exit %d: %r" % (r.returncode, r.stderr[-500:]))
raw = open(os.path.join(work, b"b.jsonl"), "rb").read()
recs = []
for i, line in enumerate(raw.split(b"\n")[:-1]):
    try:
        recs.append(json.loads(line.decode("utf-8")))  # strict: invalid UTF-8 raises
    except (UnicodeDecodeError, ValueError) as e:
        bad.append("batch record %d: not valid UTF-8 JSON: %s: %r" % (i + 1, e, line[:120]))
if len(recs) != len(paths):
    bad.append("batch: %d records for %d logs" % (len(recs), len(paths)))
for rec, p in zip(recs, paths):
    want = p.decode("utf-8", "replace")
    if rec.get("log") != want:
        bad.append("batch: log %r came back as %r" % (want, rec.get("log")))
    if rec.get("name") != "crate\ufffd\u00e9\ufffd":
        bad.append("batch: package name came back as %r" % rec.get("name"))

# ---- JSON: replay --json with every byte >= 0x80 in a package name ----------
args = [sw.encode(), b"replay", paths[0x7f], b"--json", b"--settle", b"0"]
for k, s in enumerate(high + seqs):
    sc = os.path.join(work, b"p%03d.ini" % k)
    open(sc, "wb").write(named(b"p%03d_" % k + s))
    args += [b"-s", sc]
r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
try:
    j = json.loads(r.stdout.decode("utf-8"))
    if j["log"] != paths[0x7f].decode("utf-8", "replace"):
        bad.append("replay --json: log %r" % j["log"])
    got = [p["name"] for p in j["packages"]]
    want = [(b"p%03d_" % k + s).decode("utf-8", "replace") for k, s in enumerate(high + seqs)]
    for g, w in zip(got, want):
        if g != w:
            bad.append("replay --json: package %r came back as %r" % (w, g))
    if len(got) != len(want):
        bad.append("replay --json: %d packages, expected %d" % (len(got), len(want)))
except (UnicodeDecodeError, ValueError, KeyError) as e:
    bad.append("replay --json: not valid UTF-8 JSON (exit %d): %s" % (r.returncode, e))

# ---- CSV: formula-like text cells neutralised, numbers kept -----------------
lead = [b"=", b"+", b"-", b"@", b"\t", b"\r"]
cpaths = []
for k, c in enumerate([b"=", b"+", b"@"]):  # a log may not begin with '-'
    p = os.path.join(work, c + b"HYPERLINK(1)%d.csv" % k)
    shutil.copy(log, p)
    cpaths.append(p)
man = os.path.join(work, b"m.txt")
open(man, "wb").write(b"".join(b"'%s'\n" % os.path.basename(p) for p in cpaths))
scenes = []
for k, c in enumerate(lead):
    sc = os.path.join(work, b"f%d.ini" % k)
    nm = c + b"SUM(A1)" if c not in (b"\t", b"\r") else b"x"  # INI trims the name
    open(sc, "wb").write(named(nm))
    scenes += [b"-s", sc]
r = subprocess.run([sw.encode(), b"batch", b"--manifest", man, b"-q", b"-o",
                    os.path.join(work, b"c.jsonl"), b"--csv", os.path.join(work, b"c.csv")]
                   + scenes, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
if r.returncode != 0:
    bad.append("batch (csv): exit %d: %r" % (r.returncode, r.stderr[-500:]))
rows = list(csv.reader(io.StringIO(open(os.path.join(work, b"c.csv"), encoding="utf-8",
                                        newline="").read())))
head, rows = rows[0], rows[1:]
recs = [json.loads(l) for l in open(os.path.join(work, b"c.jsonl"), encoding="utf-8")]
if len(rows) != len(recs) or len(rows) != 3 * len(lead):
    bad.append("batch (csv): %d rows, %d records, expected %d" % (len(rows), len(recs),
                                                                3 * len(lead)))
text_cols = {"log", "job", "status", "package", "model", "verdict", "scheme", "start_absolute",
             "messages"}
for row, rec in zip(rows, recs):
    cells = dict(zip(head, row))
    for col, v in cells.items():
        if col in text_cols:
            if v[:1] in ("=", "+", "-", "@", "\t", "\r"):
                bad.append("batch --csv: %s cell %r not neutralised" % (col, v))
            if v.startswith("'"):
                orig = rec.get({"package": "name"}.get(col, col))
                if isinstance(orig, str) and v[1:] != orig:
                    bad.append("batch --csv: %s %r is not \"'\" + %r" % (col, v, orig))
        elif v != "":
            try:
                float(v)
            except ValueError:
                bad.append("batch --csv: number cell %s = %r" % (col, v))
    if not cells["log"].startswith("'"):
        bad.append("batch --csv: log %r kept its leading character" % cells["log"])
    if rec["name"] != "x" and not cells["package"].startswith("'"):
        bad.append("batch --csv: package %r" % cells["package"])
if not any(c.startswith("-") for row in rows for c in row[5:]):
    bad.append("batch --csv: no negative number left as it is (the check saw none)")
# replay --out: the package column of the state file
sc = os.path.join(work, b"eq.ini")
open(sc, "wb").write(named(b"=cmd|' /C calc'!A0"))
r = subprocess.run([sw.encode(), b"replay", log, b"-s", sc, b"-q", b"--out",
                    os.path.join(work, b"st.csv")], stdout=subprocess.PIPE,
                   stderr=subprocess.PIPE)
st = list(csv.reader(open(os.path.join(work, b"st.csv"), encoding="utf-8", newline="")))
if st[1][1] != "'=cmd|' /C calc'!A0":
    bad.append("replay --out: package cell %r" % st[1][1])

for b in bad[:40]:
    print("FAIL:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY
echo "ok"
