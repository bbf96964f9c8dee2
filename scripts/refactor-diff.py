#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compare two results of scripts/refactor-check.sh: BEFORE and AFTER.

    scripts/refactor-diff.py BEFORE AFTER [--ipc-tolerance 0.03]

Every file of BEFORE/out must be in AFTER/out and the other way round.  A
file is the same when its bytes are (OUTDIR, which some outputs name,
aside), or when both are JSON (one document, or JSON Lines) that parse to
the same values: the same keys in the same order, the same strings,
booleans and nulls, and numbers equal as they were printed (%.9g: 3 and
3.0, 1e-05 and 1e-5 are one number).  A JSON writer may change its layout
and nothing else.  The instructions per sample (ipc.txt) must agree
within the tolerance (3 % unless told).

Exit 0 when everything is the same, 1 otherwise, listing what differs."""
import argparse
import json
import os
import sys


def pairs(kv):
    return ("object", kv)


def load(data):
    """The JSON values of data (a document or JSON Lines), or None."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return None
    try:
        return [json.loads(text, object_pairs_hook=pairs)]
    except ValueError:
        pass
    lines = [ln for ln in text.split("\n") if ln.strip()]
    if not lines:
        return None
    try:
        return [json.loads(ln, object_pairs_hook=pairs) for ln in lines]
    except ValueError:
        return None


def number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def same(a, b, where, out):
    """a and b are the same value; where the first difference is into out."""
    if number(a) and number(b):
        if float(a) == float(b) or "%.9g" % a == "%.9g" % b:
            return True
        out.append("%s: %r != %r" % (where, a, b))
        return False
    if isinstance(a, tuple) and isinstance(b, tuple):
        ka, kb = [k for k, _ in a[1]], [k for k, _ in b[1]]
        if ka != kb:
            out.append("%s: keys %s != %s" % (where, ka, kb))
            return False
        return all(same(x, y, "%s.%s" % (where, k), out)
                   for (k, x), (_, y) in zip(a[1], b[1]))
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append("%s: %d items != %d" % (where, len(a), len(b)))
            return False
        return all(same(x, y, "%s[%d]" % (where, i), out) for i, (x, y) in enumerate(zip(a, b)))
    if type(a) is not type(b) or a != b:
        out.append("%s: %r != %r" % (where, a, b))
        return False
    return True


def ipc(path):
    d = {}
    for line in open(path):
        f = line.split()
        if f:
            d[" ".join(f[:-1])] = int(f[-1])
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--ipc-tolerance", type=float, default=0.03)
    a = ap.parse_args()
    a.before, a.after = a.before.rstrip("/"), a.after.rstrip("/")
    bo, ao = os.path.join(a.before, "out"), os.path.join(a.after, "out")
    names_b, names_a = set(os.listdir(bo)), set(os.listdir(ao))
    bad = []
    for n in sorted(names_b - names_a):
        bad.append("only in %s: %s" % (a.before, n))
    for n in sorted(names_a - names_b):
        bad.append("only in %s: %s" % (a.after, n))
    json_same = 0
    for n in sorted(names_b & names_a):
        # the OUTDIR of each run is named in some outputs (boundary's
        # message, forensics' command line): one word for both
        x = open(os.path.join(bo, n), "rb").read().replace(os.fsencode(a.before), b"OUTDIR")
        y = open(os.path.join(ao, n), "rb").read().replace(os.fsencode(a.after), b"OUTDIR")
        if x == y:
            continue
        # refactor-check writes forensics' "modified" as a bare M: a string
        # for the parser
        x, y = (z.replace(b'"modified": M', b'"modified": "M"') for z in (x, y))
        if x == y:
            continue
        jx, jy = load(x), load(y)
        why = []
        if jx is not None and jy is not None and same(jx, jy, n, why):
            json_same += 1
            continue
        bad.append(why[0] if why else "%s: differs (not JSON)" % n)
    files = len(names_b & names_a)
    print("refactor-diff: %d files, %d byte-identical, %d the same JSON in another layout"
          % (files, files - json_same - sum(1 for b in bad if not b.startswith("only")),
             json_same))
    ib, ia = os.path.join(a.before, "ipc.txt"), os.path.join(a.after, "ipc.txt")
    if os.path.exists(ib) and os.path.exists(ia):
        pb, pa = ipc(ib), ipc(ia)
        for k in pb:
            if k not in pa:
                bad.append("ipc.txt: %s missing after" % k)
                continue
            r = (pa[k] - pb[k]) / pb[k] if pb[k] else 0.0
            print("refactor-diff: ipc %-28s %8d -> %8d (%+.2f %%)" % (k, pb[k], pa[k], 100 * r))
            if abs(r) > a.ipc_tolerance:
                bad.append("ipc.txt: %s changed by %+.2f %%" % (k, 100 * r))
    for b in bad:
        print("refactor-diff: " + b, file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
