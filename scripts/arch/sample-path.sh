#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The path of one sample through the engine, as files.  The library's
# sources are compiled with -finstrument-functions into
# scripts/arch/sample_path.c, which records the functions entered while one
# sample is pushed; addr2line turns them into the files that define them
# (a header for an inline function).  A function called again by the same
# caller (a loop over steps, stages or packages) is the same path and is
# kept once.  Along the calls, in order:
#   entries      calls into another file than the caller's
#   re-entries   such calls into a file the path had entered before
# Every 25th sample of sample_logs/hard-stop-overturn.csv from 2.5 s to
# 4.5 s (stuck, uplift, rocking, impacts, tip, overturn) is traced for the
# bare block, the frame and a cushion; the worst sample of each is printed.
#
#   scripts/arch/sample-path.sh [-v]      (-v: the worst sample's path)
set -eu
cd "$(dirname "$0")/../.."
VERBOSE=${1:-}
OUT=${TMPDIR:-/tmp}/sw-sample-path
mkdir -p "$OUT"
BUILD=${BUILD:-build}
[ -f "$BUILD/include/swaywatch/version.h" ] ||
    { echo "sample-path: build $BUILD first (for version.h)" >&2; exit 2; }
# shellcheck disable=SC2046
cc -std=c11 -O2 -g -no-pie -finstrument-functions -D_XOPEN_SOURCE=700 \
    -Iinclude -I"$BUILD/include" $(find src/lib -type d | sed 's/^/-I/') \
    scripts/arch/sample_path.c $(find src/lib -name '*.c' | sort) \
    -o "$OUT/sample_path" -lgsl -lgslcblas -lcsv -linih -lm -lpthread
awk -F, 'NR > 1 { print $1 "," $2 }' sample_logs/hard-stop-overturn.csv >"$OUT/log.csv"
cat >"$OUT/cushion.ini" <<'INI'
[package]
name = crate-on-cushion
height = 2.0
width = 0.728
mass = 1000
[cushion]
omega = 40
zeta = 0.05
INI
python3 - "$OUT" "$VERBOSE" <<'PY'
import os, subprocess, sys

out, verbose = sys.argv[1], sys.argv[2] == "-v"
exe = os.path.join(out, "sample_path")


def tree(scene, n):
    rec = subprocess.run([exe, scene, os.path.join(out, "log.csv"), str(n), "default"],
                         capture_output=True, text=True).stdout.splitlines()
    locs = subprocess.run(["addr2line", "-e", exe], input="\n".join(r.split()[1] for r in rec),
                          capture_output=True, text=True).stdout.splitlines()
    root = {"f": None, "kids": [], "seen": set()}
    stack = [root]
    for r, loc in zip(rec, locs):
        d, addr = r.split()
        f = os.path.basename(loc.split(":")[0])
        if f.startswith("?"):
            continue
        if d == ">":
            node = {"f": f, "kids": [], "seen": set()}
            parent = stack[-1]
            if addr not in parent["seen"]:
                parent["seen"].add(addr)
                parent["kids"].append(node)
            stack.append(node)
        elif len(stack) > 1:
            stack.pop()
    return root["kids"][0] if root["kids"] else None


def path(t):
    steps, entered = [t["f"]], {t["f"]}
    ent = re = 0

    def visit(n):
        nonlocal ent, re
        for k in n["kids"]:
            if k["f"] != n["f"]:
                ent += 1
                re += k["f"] in entered
                entered.add(k["f"])
                steps.append("%s>%s" % (n["f"], k["f"]))
            visit(k)

    visit(t)
    return ent, re, steps


for name, scene in (("bare", "sample_logs/crate.ini"), ("frame", "sample_logs/crate-on-frame.ini"),
                    ("cushion", os.path.join(out, "cushion.ini"))):
    worst = None
    for n in range(2500, 4501, 25):
        t = tree(scene, n)
        if t:
            e, r, s = path(t)
            if not worst or (r, e) > (worst[1], worst[0]):
                worst = (e, r, n, s)
    print("%-8s worst sample %d: %d entries, %d re-entries" % (name, worst[2], worst[0], worst[1]))
    if verbose:
        print("  " + "  ".join(worst[3][1:]))
PY
