#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# watch shows what the bus says, never what a hostile message would make
# the terminal do: state and alarm messages whose name and text hold every
# control byte (C0, DEL), every C1 control as UTF-8 (U+0080-U+009F: CSI,
# OSC, ...), raw bytes 0x80-0xff, an OSC title sequence and a CSI colour
# sequence.  'watch --once' (plain text) must print valid UTF-8 without a
# single control character but the line ends, each one shown as '?', and
# the printable text around them kept; a name cut to the table's width is
# cut between characters.  A package with two planes (state_t.plane) has
# two rows, the lateral one under it.  The messages reach watch from an
# lcm-logger file (-l file://...), no network needed.
# usage: watch_text.sh SWAYWATCH PYTHON_TYPES_DIR
set -eu
SW=$1 PYDIR=$2
"$SW" --help | grep -q '^  watch' || { echo "no watch in this build: skipped"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/once.txt" ] && cat -v "$T/once.txt" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}

PYTHONPATH=$PYDIR python3 - "$T/bus.lcmlog" <<'PY'
import struct, sys
from swaywatch import alarm_t, state_t

def i8(b, n):
    b = bytes(b)[: n - 1]
    return [x - 256 if x > 127 else x for x in b + bytes(n - len(b))]

c0 = bytes(range(1, 32)) + b"\x7f"
c1 = [chr(c).encode() for c in range(0x80, 0xA0)]  # C2 80 .. C2 9F, one each
raw = bytes(range(0x80, 0x100))
osc = b"\x1b]0;PWNED\x07"
csi = b"\x9b31m" + b"\xc2\x9b" + b"32m"

events = []
t0 = 1_700_000_000_000_000
# (the package table shows 16 columns of a name)
for k, name in enumerate([b"A" + c0[:12] + b"Z", b"B" + b"".join(c1[:12]) + b"Z",
                          b"C" + raw[:12] + b"Z", b"D" + osc + b"Z", b"F" + c0[12:24] + b"Z",
                          b"G" + b"".join(c1[12:24]) + b"Z",
                          ("H" + "\u00e9" * 9).encode()]):
    s = state_t()
    s.utime, s.seq, s.name = t0 + k, k, i8(name, 64)
    s.model, s.phase, s.theta, s.margin, s.reserve_g = 0, 1, 0.1, 0.5, -1.0
    events.append((t0 + k, "SWAY_STATE", s.encode()))
for k, text in enumerate([b"x" + c0 + b"y", b"x" + b"".join(c1) + b"y", b"x" + raw[:100] + b"y",
                          b"x" + osc + csi + b"y", b"x" + raw[100:] + b"y"]):
    a = alarm_t()
    a.utime, a.seq, a.name = t0 + 10 + k, k, i8(b"E" + b"".join(c1[24:]) + b"\x1b[2J", 64)
    a.kind, a.level, a.text = 9, 2, i8(text, 128)
    a.theta, a.margin, a.reserve_g = 0.0, 1.0, -1.0
    events.append((t0 + 10 + k, "SWAY_ALARM", a.encode()))
# a package that rocks in two planes (the lateral state first, as the
# monitor sends them): two rows, the lateral one under it, overturned
for k, (plane, phase, theta) in enumerate([(1, 2, -1.5708), (0, 0, 0.0)]):
    s = state_t()
    s.utime, s.seq, s.name = t0 + 20, 7 + k, i8(b"P2", 64)
    s.model, s.phase, s.theta, s.margin, s.reserve_g = 0, phase, theta, 0.5, -1.0
    s.plane = plane
    events.append((t0 + 20 + k, "SWAY_STATE", s.encode()))
# a last event much later: the log does not end while watch listens
events.append((t0 + 60_000_000, "OTHER", b"x"))
with open(sys.argv[1], "wb") as f:
    for n, (ts, ch, data) in enumerate(events):
        f.write(struct.pack(">IqqII", 0xEDA1DA01, n, ts, len(ch), len(data)) + ch.encode() + data)
PY

rc=0
"$SW" watch --once --wait 1.5 -l "file://$T/bus.lcmlog" >"$T/once.txt" 2>"$T/err" || rc=$?
[ "$rc" -eq 0 ] || fail "watch --once: exit $rc"
python3 - "$T/once.txt" <<'PY' || fail "watch --once printed control characters"
import sys
raw = open(sys.argv[1], "rb").read()
bad = []
try:
    text = raw.decode("utf-8")
except UnicodeDecodeError as e:
    bad.append("not valid UTF-8: %s" % e)
    text = raw.decode("utf-8", "replace")
for i, ch in enumerate(text):
    c = ord(ch)
    if (c < 0x20 and ch != "\n") or 0x7F <= c <= 0x9F:
        bad.append("U+%04X at %d: %r" % (c, i, text[max(0, i - 20):i + 20]))
# what was printable is still there, the controls as '?'
for want in ("A" + "?" * 12 + "Z", "B" + "?" * 12 + "Z", "C" + "?" * 12 + "Z", "D?]0;PWNED?Z",
             "F" + "?" * 12 + "Z", "G" + "?" * 12 + "Z", "x" + "?" * 32 + "y",
             "x" + "?" * 100 + "y", "x" + "?" * 28 + "y", "x?]0;PWNED??31m?32my",
             "E" + "?" * 9 + "[2J", "H" + "\u00e9" * 7 + " "):
    if want not in text:
        bad.append("missing %r" % want)
# the package with two planes: its row, then its lateral plane's; one
# plane only for the others
lines = text.split("\n")
rows = [i for i, l in enumerate(lines) if l.startswith("P2 ")]
if len(rows) != 1 or not lines[rows[0] + 1].startswith("  sideways ") or \
        "OVERTURNED" not in lines[rows[0] + 1] or "OVERTURNED" in lines[rows[0]]:
    bad.append("the two planes of P2 are not shown as such: %r" % lines)
if sum("sideways" in l for l in lines) != 1:
    bad.append("a package with one plane shown with a lateral row")
for b in bad[:20]:
    print("FAIL:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY
echo "ok"
