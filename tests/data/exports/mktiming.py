#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""mktiming.py - writes the timing-shaped export files timing-*.csv of this
folder: synthetic drives, each timed the way a real kind of logger times
its rows, for tests/cli/timing_exports.sh (README.md says what each holds).

    python3 tests/data/exports/mktiming.py [OUTDIR]

Deterministic (a fixed seed per file); Python 3 standard library only.
The drives are quiet roads with one braking of 0.3 g: the sample crate
(sample_logs/crate.ini) stays upright on every one, so a verdict is all
the timing has to allow.
"""
import math
import os
import random
import sys

G0 = 9.80665


def road(t, rnd_phase):
    """m/s^2: road vibration and a 0.3 g braking from 6 s to 9 s."""
    a = 0.15 * math.sin(2 * math.pi * 1.7 * t + rnd_phase) + 0.08 * math.sin(2 * math.pi * 11.3 * t)
    if 6.0 <= t <= 9.0:
        a -= 0.3 * G0 * math.sin(math.pi * (t - 6.0) / 3.0)
    return a


def write(path, header, rows):
    with open(path, "w", newline="") as f:
        f.write(header + "\n")
        for r in rows:
            f.write(r + "\n")


def can_merged(out):
    """CAN frames of four IDs merged in time order, as a bus logger's signal
    export writes them: one row per frame, every signal with its latest
    value.  The acceleration frame (0x3E9) is the 10 Hz one; the others
    come every 10, 20 and 50 ms with their own jitter, so rows are 0 to
    25 ms apart; three times the other IDs fall silent for up to 1 s and
    only the acceleration frame goes on.  Nothing is missing."""
    rnd = random.Random(24001)
    ids = [(0x0C1, 0.010), (0x1A0, 0.020), (0x3E9, 0.100), (0x4B0, 0.050)]
    nxt = [rnd.uniform(0, p) for _, p in ids]
    quiet = [(4.0, 4.6), (11.0, 12.0), (15.5, 16.3)]
    phase = rnd.uniform(0, 6.28)
    accel_g, speed, rpm = 0.0, 52.0, 1800
    rows, last = [], -1.0
    while True:
        k = min(range(len(ids)), key=lambda i: nxt[i])
        t = nxt[k]
        if t > 20.0:
            break
        fid, per = ids[k]
        nxt[k] += per * (1 + rnd.uniform(-0.08, 0.08))
        if fid != 0x3E9 and any(a <= t < b for a, b in quiet):
            continue
        t = round(t, 6)
        if t <= last:
            t = last + 1e-6
        last = t
        if fid == 0x3E9:
            accel_g = road(t, phase) / G0
        elif fid == 0x1A0:
            speed = max(0.0, 52.0 - (8.0 if t > 9 else 0.0) + rnd.uniform(-0.2, 0.2))
        elif fid == 0x0C1:
            rpm = int(1800 + 200 * math.sin(t))
        rows.append("%.6f,0x%03X,%.4f,%.1f,%d" % (t, fid, accel_g, speed, rpm))
    write(out, "Time [s],ID,Accel X [g],Vehicle speed [km/h],Engine speed [rpm]", rows)


def event_driven(out):
    """A phone app that writes a row when the reading changes by more than
    0.1 m/s^2, and at least every 0.5 s: half a second apart while the car
    is parked (the first and last 10 s), a few ms apart on the road."""
    rnd = random.Random(24002)
    phase = rnd.uniform(0, 6.28)
    rows, t, last_t, last_a = [], 0.0, -1.0, None
    while t < 70.0:
        parked = t < 10.0 or t > 60.0
        a = 0.004 * rnd.gauss(0, 1) if parked else road(t - 10.0, phase) + 0.02 * rnd.gauss(0, 1)
        if last_a is None or abs(a - last_a) > 0.1 or t - last_t >= 0.5:
            rows.append("%.4f,%.4f" % (t, a))
            last_t, last_a = t, a
        t += 0.002  # the sensor's own rate; rows only on change
    write(out, "time_s,acc_x_ms2", rows)


def bursts(out):
    """A shock logger in triggered mode: 10 Hz, and 1 kHz for half a second
    whenever the bed moves by more than 0.15 g (the braking, the bumps)."""
    rnd = random.Random(24003)
    phase = rnd.uniform(0, 6.28)
    bumps = [18.3, 33.1, 47.9, 52.2, 70.4]
    rows, t, until = [], 0.0, -1.0

    def a_at(x):
        a = road(x, phase)
        for b in bumps:
            if b <= x < b + 0.12:
                a += 2.0 * math.sin(math.pi * (x - b) / 0.12)
        return a

    while t < 90.0:
        a = a_at(t)
        rows.append("%.3f,%.4f" % (t, a))
        if abs(a) > 0.15 * G0 and t >= until:
            until = t + 0.5
        t = round(t + (0.001 if t < until else 0.1), 3)
    write(out, "t [s],a [m/s2]", rows)


def rate_change(out):
    """A logger reconfigured while it records: 12 s at 200 Hz, 12 s at
    25 Hz, 3 s at 1 kHz, each with a little jitter."""
    rnd = random.Random(24004)
    phase = rnd.uniform(0, 6.28)
    rows, t = [], 0.0
    for end, rate in ((12.0, 200.0), (24.0, 25.0), (27.0, 1000.0)):
        while t < end:
            rows.append("%.5f,%.4f" % (t, road(t % 12.0, phase)))
            t += (1 + rnd.uniform(-0.03, 0.03)) / rate
    write(out, "time,accel", rows)


def fifo_batches(out):
    """An IMU sampling at 400 Hz whose FIFO is read every 32 samples (80 ms,
    give or take the host's scheduling), for 12 s; each sample is stamped
    when read, a few microseconds after the one before.  Times in
    microseconds."""
    rnd = random.Random(24005)
    phase = rnd.uniform(0, 6.28)
    rows, t_read = [], 0.0
    while t_read < 12.0:
        t_read += 32 / 400.0 * (1 + rnd.uniform(-0.15, 0.15))
        us = int(t_read * 1e6)
        for i in range(32):
            t_sample = t_read - (31 - i) / 400.0
            us += rnd.randint(3, 9)
            rows.append("%d,%.4f" % (us, road(t_sample, phase) / G0))
    write(out, "timestamp_us,ax_g", rows)


def whole_ms(out):
    """A 1600 Hz logger that writes its time in whole milliseconds: one or
    two rows per millisecond."""
    rnd = random.Random(24006)
    phase = rnd.uniform(0, 6.28)
    rows = []
    for i in range(int(5.0 * 1600)):
        t = i / 1600.0
        rows.append("%d,%.4f" % (int(t * 1000), road(t + 5.0, phase) + 0.02 * rnd.gauss(0, 1)))
    write(out, "Time (ms),Accel (m/s^2)", rows)


FILES = {
    "timing-can-merged.csv": can_merged,
    "timing-event-driven.csv": event_driven,
    "timing-bursts.csv": bursts,
    "timing-rate-change.csv": rate_change,
    "timing-fifo-batches.csv": fifo_batches,
    "timing-1600hz-whole-ms.csv": whole_ms,
}


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, fn in FILES.items():
        fn(os.path.join(outdir, name))


if __name__ == "__main__":
    main()
