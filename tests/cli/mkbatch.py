#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Write the logs and the manifest of a test batch into DIR.

usage: mkbatch.py DIR SCENE_DIR

Twenty logs of lengths from 1 s to 40 s (a factor of 40), at 200 to
1000 Hz: road noise (a fixed seed, so every run writes the same bytes) with
a braking pulse in some of them, strong enough to overturn a crate on its
frame in a few; and six that fail, each for a different reason.  The
manifest lists them all, in an order unrelated to their length; some lines
carry their own options (units, a scene of their own).  Python 3 standard
library only.
"""
import math
import os
import random
import sys


def write_log(path, seconds, rate, brake, unit_g=False, delim=","):
    rnd = random.Random(hash((seconds, rate, brake)) & 0xFFFF)
    n = int(round(seconds * rate)) + 1
    g = 9.80665
    with open(path, "w") as f:
        f.write("t_s%saccel_%s\n" % (delim, "g" if unit_g else "mps2"))
        for i in range(n):
            t = i / rate
            a = 0.2 * math.sin(2 * math.pi * 7.3 * t) + rnd.gauss(0.0, 0.1)
            # a braking pulse (sin^2) of peak brake m/s^2, 1.5 s long, at a third
            t0 = seconds / 3.0
            if brake and t0 <= t <= t0 + 1.5:
                a -= brake * math.sin(math.pi * (t - t0) / 1.5) ** 2
            if unit_g:
                a /= g
            f.write("%.6f%s%.6f\n" % (t, delim, a))


def main():
    out, scenes = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    lines = []
    # (name, seconds, rate, brake m/s^2)
    good = [
        ("a01", 12, 500, 0), ("a02", 1, 1000, 2), ("a03", 40, 200, 4.5), ("a04", 3, 1000, 0),
        ("a05", 25, 400, 3.2), ("a06", 2, 500, 5.5), ("a07", 8, 1000, 1), ("a08", 30, 200, 0),
        ("a09", 5, 1000, 4), ("a10", 16, 250, 2.5), ("a11", 1.5, 800, 0), ("a12", 20, 500, 3.8),
    ]
    for name, sec, rate, brake in good:
        write_log(os.path.join(out, name + ".csv"), sec, rate, brake)
        lines.append("%s/%s.csv" % (out, name))
    # the same drive as a12, in g and ms with semicolons: its own options
    path = os.path.join(out, "g-units.csv")
    write_log(path, 20, 500, 3.8, unit_g=True, delim=";")
    with open(path) as f:
        rows = f.read().splitlines()
    with open(path, "w") as f:
        f.write("time;accel\n")  # a header that says no unit
        for r in rows[1:]:
            t, a = r.split(";")
            f.write("%.3f;%s\n" % (float(t) * 1000.0, a))
    lines.append("'%s' --time-unit ms --accel-unit g  # its own units" % path)
    # a log with a scene of its own (the line's --scene replaces the batch's)
    lines.append("%s/a05.csv --scene %s/crate-on-cushion.ini" % (out, scenes))
    # failures: missing, empty, not numbers, refused by the gate (a rate
    # of 1 Hz: seconds written as ms), a header that names no column, a
    # folder
    lines.append("%s/missing.csv" % out)
    open(os.path.join(out, "empty.csv"), "w").close()
    lines.append("%s/empty.csv" % out)
    with open(os.path.join(out, "words.csv"), "w") as f:
        f.write("this,is\nnot,a\nlog,at all\n")
    lines.append("%s/words.csv" % out)
    with open(os.path.join(out, "slow.csv"), "w") as f:
        f.write("t_s,accel_mps2\n")
        for i in range(400):
            f.write("%d,%.3f\n" % (i, 0.1 * math.sin(i)))  # ms written under a header of s
    lines.append("%s/slow.csv" % out)
    with open(os.path.join(out, "which.csv"), "w") as f:
        f.write("alpha,beta,gamma\n")
        for i in range(2000):
            f.write("%.3f,%.3f,%.3f\n" % (i / 1000.0, 0.1, 0.2))
    lines.append("%s/which.csv" % out)
    os.makedirs(os.path.join(out, "folder.csv"), exist_ok=True)
    lines.append("%s/folder.csv" % out)
    # an order unrelated to the lengths
    rnd = random.Random(7)
    rnd.shuffle(lines)
    with open(os.path.join(out, "manifest.txt"), "w") as f:
        f.write("# a test batch: %d logs\n\n" % len(lines))
        for i, l in enumerate(lines):
            f.write(l + "\n")
            if i == 5:
                f.write("   # a comment between lines\n")


if __name__ == "__main__":
    main()
