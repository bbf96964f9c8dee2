#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# docs/img/monitor.txt, the README's picture of a live run, is what
# scripts/make-doc-images.sh prints today, not an old format: the script
# runs again into a scratch folder (a private network namespace, real
# time), and every line of the committed picture, its numbers and times
# masked, must be a line the programs print now; every kind of line they
# print now (the monitor's status and alarm lines, the listener's) must be
# in the picture.  Regenerate it with 'scripts/make-doc-images.sh monitor'.
# Needs a network namespace and lcm-logplayer: exits 77 otherwise.
# usage: doc_images.sh BUILD_DIR SOURCE_DIR PYTHON_TYPES_DIR
set -eu
BUILD=$1 SRC=$2
command -v lcm-logplayer >/dev/null || { echo "doc_images.sh: no lcm-logplayer: skipped"; exit 77; }
if ! ip route get 239.255.76.67 >/dev/null 2>&1 && ! unshare -n true 2>/dev/null; then
    echo "doc_images.sh: no multicast route and no network namespace: skipped"
    exit 77
fi
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
(cd "$SRC" && OUT="$T" BUILD="$BUILD" sh scripts/make-doc-images.sh monitor >/dev/null)
python3 - "$SRC/docs/img/monitor.txt" "$T/monitor.txt" <<'PY'
import re, sys

def shape(line):
    line = re.sub(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d+Z", "T", line)
    return re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "N", line.rstrip("\n"))

def kind(line):  # the program and the kind of line, without its values
    m = re.match(r"(swaywatch: (monitor \S+|alarm)|T seq|\$|>|csv2lcmlog|package|  \w+)", shape(line))
    return m.group(1) if m else shape(line)

doc = [l for l in open(sys.argv[1])]
now = [l for l in open(sys.argv[2])]
now_shapes = {shape(l) for l in now}
stale = [l.rstrip() for l in doc if shape(l) not in now_shapes]
missing = sorted({kind(l) for l in now} - {kind(l) for l in doc})
for l in stale[:10]:
    print("doc_images.sh: docs/img/monitor.txt has a line no program prints now:\n  " + l)
for k in missing:
    print("doc_images.sh: docs/img/monitor.txt lacks the kind of line '%s'" % k)
if stale or missing:
    print("doc_images.sh: regenerate it: scripts/make-doc-images.sh monitor")
    sys.exit(1)
print("doc_images.sh: ok (%d lines)" % len(doc))
PY
