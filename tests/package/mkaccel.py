#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""mkaccel.py - write an lcm-logger file of swaywatch.accel_t samples: a
braking half-sine on x, sampled at --rate Hz, with the generated Python
types and the event log written by hand (no LCM Python module needed).

usage: PYTHONPATH=GENERATED_PYTHON mkaccel.py OUT --amplitude A --omega W
                          [--rate HZ] [--duration S] [--lead S] [--start S]
                          [--lateral]

--start S makes a log that continues one that ended before S seconds: its
samples start at S (utime and seq), the pulse at S + lead.
"""
import argparse
import math
import struct

from swaywatch import accel_t

ap = argparse.ArgumentParser()
ap.add_argument("out")
ap.add_argument("--amplitude", type=float, default=-5.0)  # m/s^2
ap.add_argument("--omega", type=float, default=10.0)      # rad/s
ap.add_argument("--rate", type=float, default=1000.0)     # Hz
ap.add_argument("--duration", type=float, default=3.0)    # s
ap.add_argument("--lead", type=float, default=0.1)        # s of still bed first
ap.add_argument("--start", type=float, default=0.0)    # s, time of the first sample
ap.add_argument("--channel", default="ACCEL")
ap.add_argument("--lateral", action="store_true")  # the pulse on y (across the truck), not x
a = ap.parse_args()

t0_us = 1_700_000_000_000_000  # a fixed start: the log is the same every run
n = int(round(a.duration * a.rate)) + 1
with open(a.out, "wb") as f:
    for i in range(n):
        t = a.start + i / a.rate
        tp = t - a.start - a.lead
        m = accel_t()
        m.utime = t0_us + int(round(t * 1e6))
        m.seq = int(round(a.start * a.rate)) + i
        pulse = a.amplitude * math.sin(a.omega * tp) if 0 <= tp <= math.pi / a.omega else 0.0
        if a.lateral:
            m.ay = pulse
        else:
            m.ax = pulse
        data = m.encode()
        ch = a.channel.encode()
        f.write(struct.pack(">IqqII", 0xEDA1DA01, i, m.utime, len(ch), len(data)) + ch + data)
print("mkaccel.py: %d samples in %s" % (n, a.out))
