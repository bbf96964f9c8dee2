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
#   re-entries   such calls into a file the path had entered before,
#                of which
#     into leaves     into a file that calls no other file on this path
#                     (input.h, numeric.h, hermite.h: reached from every
#                     layer that uses them, which is no circle)
#     back up         into a file the path is still inside of, above the
#                     caller (a call back up, as a lower layer calling
#                     the phase machine would be)
# A static inline function has a copy in each unit that calls it, and
# gcc's line table names a few copies after the unit's own file: each is
# named after the header most of its copies name.
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


files = {}  # address -> file, and function -> the files its copies name


def where(addrs):
    new = sorted(set(addrs) - set(files))
    got = subprocess.run(["addr2line", "-f", "-e", exe], input="\n".join(new),
                         capture_output=True, text=True).stdout.splitlines()
    for a, fn, loc in zip(new, got[0::2], got[1::2]):
        files[a] = (fn, os.path.basename(loc.split(":")[0]))


def file_of(addr):
    fn, f = files[addr]
    if f.endswith(".c"):
        named = [g for (n, g) in files.values() if n == fn and g.endswith(".h")]
        if named:
            return max(set(named), key=named.count)
    return f


def tree(scene, n):
    rec = subprocess.run([exe, scene, os.path.join(out, "log.csv"), str(n), "default"],
                         capture_output=True, text=True).stdout.splitlines()
    where(r.split()[1] for r in rec)
    root = {"f": None, "kids": [], "seen": set()}
    stack = [root]
    for r in rec:
        d, addr = r.split()
        f = file_of(addr)
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
    steps, entered, callers, inside = [t["f"]], {t["f"]}, set(), [t["f"]]
    ent = re = up = 0
    into = []  # the files re-entered

    def scan(n):
        for k in n["kids"]:
            if k["f"] != n["f"]:
                callers.add(n["f"])
            scan(k)

    def visit(n):
        nonlocal ent, re, up
        for k in n["kids"]:
            if k["f"] != n["f"]:
                ent += 1
                if k["f"] in entered:
                    re += 1
                    up += k["f"] in inside[:-1]
                    into.append(k["f"])
                entered.add(k["f"])
                steps.append("%s>%s" % (n["f"], k["f"]))
            inside.append(k["f"])
            visit(k)
            inside.pop()

    scan(t)
    visit(t)
    leaves = sum(f not in callers for f in into)
    return ent, re, steps, leaves, up


for name, scene in (("bare", "sample_logs/crate.ini"), ("frame", "sample_logs/crate-on-frame.ini"),
                    ("cushion", os.path.join(out, "cushion.ini"))):
    worst = None
    for n in range(2500, 4501, 25):
        t = tree(scene, n)
        if t:
            e, r, s, lv, up = path(t)
            if not worst or (r, e) > (worst[1], worst[0]):
                worst = (e, r, n, s, lv, up)
    print("%-8s worst sample %d: %d entries, %d re-entries (%d into leaves, %d back up)" %
          (name, worst[2], worst[0], worst[1], worst[4], worst[5]))
    if verbose:
        print("  " + "  ".join(worst[3][1:]))
PY
