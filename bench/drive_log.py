#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A long drive for the forensics and replay benchmarks (Python 3 stdlib
only): the longitudinal acceleration of a truck bed at 1 kHz, shaped like a
real drive, the same bytes on every machine for a seed.

    python3 bench/drive_log.py [--minutes M] [--seed S] [--shock A] [--sway A] > drive.csv

- a sway of 0.8 m/s^2 at 1.3 Hz (the body's pitch on its suspension under
  a steady road), its phase drifting slowly;
- white noise of 0.3 m/s^2 rms (road roughness above the sway);
- every 10 minutes, from 5 minutes on, a braking shock: a half-sine of
  -6 m/s^2 lasting 0.2 s (a hard brake on a pothole), well above the
  crate's uplift threshold g tan(alpha) = 3.57 m/s^2.
An hour (the default) is 3,600,001 rows, "time_s,accel_ms2", time in s
with 3 decimals, acceleration in m/s^2 with 5.  --shock and --sway change
the two amplitudes (m/s^2; --shock 0: a drive without shocks, where no
moment stands out).
"""
import argparse
import math
import random
import sys

RATE = 1000.0  # Hz
SWAY_HZ = 1.3  # Hz
SWAY_AMP = 0.8  # m/s^2
NOISE_RMS = 0.3  # m/s^2
SHOCK_EVERY = 600.0  # s
SHOCK_FIRST = 300.0  # s
SHOCK_AMP = -6.0  # m/s^2 (braking)
SHOCK_LEN = 0.2  # s


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--minutes", type=float, default=60.0)
    ap.add_argument("--seed", type=int, default=20260611)
    ap.add_argument("--shock", type=float, default=-SHOCK_AMP, help="m/s^2, braking")
    ap.add_argument("--sway", type=float, default=SWAY_AMP, help="m/s^2")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    n = int(round(a.minutes * 60.0 * RATE)) + 1
    out = sys.stdout
    out.write("time_s,accel_ms2\n")
    phase, buf = 0.0, []
    w = 2.0 * math.pi * SWAY_HZ
    for i in range(n):
        t = i / RATE
        # a slow random walk of the phase: the sway is not one pure tone
        phase += rng.gauss(0.0, 0.002)
        acc = a.sway * math.sin(w * t + phase) + rng.gauss(0.0, NOISE_RMS)
        u = (t - SHOCK_FIRST) % SHOCK_EVERY if t >= SHOCK_FIRST else -1.0
        if 0.0 <= u <= SHOCK_LEN:
            acc -= a.shock * math.sin(math.pi * u / SHOCK_LEN)
        buf.append("%.3f,%.5f\n" % (t, acc))
        if len(buf) >= 65536:
            out.write("".join(buf))
            buf = []
    out.write("".join(buf))


if __name__ == "__main__":
    main()
