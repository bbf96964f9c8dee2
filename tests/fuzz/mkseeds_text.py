#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the seed corpora of the text targets: csv and timecol (the logger
and app exports of tests/data/exports/, cut to their first lines, and the
bad CSV logs of tests/badinput/csv/), scene (the hostile scenes of
tests/badinput/scenes/) and gnuplot (names and titles that try to end a
gnuplot string or command).  The input formats are at the top of each
fuzz_<target>.c.  The hand-written seeds already in the corpus folders are
left as they are; files this script writes start with "x-", "bad-" or
"g-".

usage: mkseeds_text.py SOURCE_DIR CORPUS_DIR
  (SOURCE_DIR: the top of the source tree)"""
import os
import sys

SRC, OUT = sys.argv[1], sys.argv[2]
LINES = 24  # lines kept of an export: the header, a preamble, first rows


def put(target, name, data):
    os.makedirs(os.path.join(OUT, target), exist_ok=True)
    with open(os.path.join(OUT, target, name), "wb") as f:
        f.write(data)


def head(path, n=LINES):
    with open(path, "rb") as f:
        return b"".join(f.readlines()[:n])


# csv: o0 0 (delimiter detected, header detected, no flip), o1 0 (no column
# given), o2 1 (with infer: the header chooses), seed 0xc0 (infer on, the
# decimal comma detected)
CSV_INFER = bytes([0x00, 0x00, 0x01, 0xC0])
# ... and the defaults: columns 1 and 2, no infer
CSV_PLAIN = bytes([0x00, 0x00, 0x00, 0x00])
# timecol: o0 3 (date order detected, delimiter detected, header detected,
# decimal comma detected, preamble found), o1 0 (nothing given)
TIMECOL = bytes([0x03, 0x00])
# ... the day first given (o0 1)
TIMECOL_DMY = bytes([0x01, 0x00])

exports = os.path.join(SRC, "tests", "data", "exports")
for name in sorted(os.listdir(exports)):
    if not name.endswith(".csv"):
        continue
    text = head(os.path.join(exports, name))
    stem = name[:-4]
    put("csv", "x-" + stem, CSV_INFER + text)
    put("timecol", "x-" + stem, TIMECOL + text)
    if "dayfirst" in stem or "monthfirst" in stem:
        put("timecol", "x-" + stem + "-dmy", TIMECOL_DMY + text)

# the reader's limits as the fuzz build sets them (CMakeLists.txt): a line
# over 4 KiB, and a look-ahead ended by its 16 KiB before its 256 rows
put("csv", "x-line-over-limit", CSV_PLAIN + b"t,a\n0,1\n0.001," + b"1" * 5000 + b"\n0.002,3\n")
wide = b"".join(b"%.3f,%s\n" % (k * 1e-3, b"0.5" + b"0" * 160) for k in range(120))
put("csv", "x-ahead-bytes", CSV_PLAIN + b"t,a\n" + wide)

badcsv = os.path.join(SRC, "tests", "badinput", "csv")
for name in sorted(os.listdir(badcsv)):
    text = head(os.path.join(badcsv, name), 40)
    put("csv", "bad-" + name[:-4], CSV_PLAIN + text)

# scene: the text alone (no NUL): a default pulse is pushed
scenes = os.path.join(SRC, "tests", "badinput", "scenes")
for name in sorted(os.listdir(scenes)):
    with open(os.path.join(scenes, name), "rb") as f:
        put("scene", "bad-" + name[:-4], f.read())

# gnuplot: options, then the file name, the title and three package names
# (NUL between them); o 0x36: .svg, three packages, events, gaps
GP = bytes([0x36])
inject = [
    b'\nsystem("touch PWNED")\n#',
    b'"\nsystem("touch PWNED")\n"',
    b"'\nsystem('touch PWNED')\n'",
    b"`touch PWNED`",
    b"\\\"; system(\"touch PWNED\"); \\\"",
    b"\r!touch PWNED\r",
    b"@GPVAL_VERSION $data {x}_^&~",
    b"\x01" + b"5\x0107\x1b[31m",
    b"\xc3\xa9t\xc3\xa9 \xff\xfe \xe2\x80\xae",
]
for i, s in enumerate(inject):
    put("gnuplot", "g-name-%d" % i, GP + s + b"\0" + b"title\0" + b"crate\0pallet\0box")
    put("gnuplot", "g-title-%d" % i, GP + b"fig\0" + s + b"\0crate\0pallet\0box")
    put("gnuplot", "g-package-%d" % i, GP + b"fig\0title\0" + s[:60] + b"\0crate\0box")
put("gnuplot", "g-png-one-package", bytes([0x01]) + b"figure\0Replay of drive.csv\0crate-A")
put("gnuplot", "g-every-control-byte",
    bytes([0x00]) + bytes(range(1, 32)) + b"\0" + bytes(range(1, 32)) + b"\x7f\0"
    + bytes(range(1, 32)))
