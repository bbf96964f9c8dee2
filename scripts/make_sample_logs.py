#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Generate the synthetic sample logs in sample_logs/ (Python 3 stdlib only).

The logs are made up, not recorded: longitudinal acceleration of a truck bed
at 1 kHz, with a fixed random seed so that every run writes the same bytes.

    python3 scripts/make_sample_logs.py [OUTDIR]      (default: sample_logs)

braking-pothole.csv      ~20 s drive: road vibration, a firm braking event,
                         a pothole shock.  The crate of crate.ini rocks but
                         stays upright.
hard-stop-overturn.csv   ~8 s: road vibration, an emergency stop ending in a
                         collision-like shock.  The crate overturns.
braking-pothole-g-ms.csv the same data as braking-pothole.csv written with
                         ';', time in ms and acceleration in g, to exercise
                         the CSV options of 'swaywatch replay'.
"""
import math
import os
import random
import sys

RATE = 1000.0           # Hz
G0 = 9.80665            # m/s^2 per g (the unit of the g variant)
SEED = 20240611


def lowpass(x, fc, q=0.7071):
    """Second-order (biquad) low-pass, RBJ cookbook, applied forward."""
    w0 = 2.0 * math.pi * fc / RATE
    al = math.sin(w0) / (2.0 * q)
    c = math.cos(w0)
    b0, b1, b2 = (1 - c) / 2, 1 - c, (1 - c) / 2
    a0, a1, a2 = 1 + al, -2 * c, 1 - al
    y, x1, x2, y1, y2 = [], 0.0, 0.0, 0.0, 0.0
    for v in x:
        o = (b0 * v + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2) / a0
        x2, x1, y2, y1 = x1, v, y1, o
        y.append(o)
    return y


def highpass(x, fc, q=0.7071):
    w0 = 2.0 * math.pi * fc / RATE
    al = math.sin(w0) / (2.0 * q)
    c = math.cos(w0)
    b0, b1, b2 = (1 + c) / 2, -(1 + c), (1 + c) / 2
    a0, a1, a2 = 1 + al, -2 * c, 1 - al
    y, x1, x2, y1, y2 = [], 0.0, 0.0, 0.0, 0.0
    for v in x:
        o = (b0 * v + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2) / a0
        x2, x1, y2, y1 = x1, v, y1, o
        y.append(o)
    return y


def road(rng, n, rms):
    """Road vibration: Gaussian noise band-limited to about 1-25 Hz, scaled
    to the given rms (m/s^2)."""
    w = [rng.gauss(0.0, 1.0) for _ in range(n)]
    v = lowpass(highpass(w, 1.0), 25.0)
    r = math.sqrt(sum(s * s for s in v) / n)
    return [s * rms / r for s in v]


def hann_pulse(t, t0, length, peak):
    """Smooth pulse sin^2 from t0 over length seconds, peak value peak."""
    if t < t0 or t > t0 + length:
        return 0.0
    return peak * math.sin(math.pi * (t - t0) / length) ** 2


def plateau(t, t0, ramp, hold, level):
    """Raised-cosine ramp up over ramp s, hold, ramp down: a braking event."""
    if t < t0:
        return 0.0
    u = t - t0
    if u < ramp:
        return level * 0.5 * (1 - math.cos(math.pi * u / ramp))
    if u < ramp + hold:
        return level
    if u < 2 * ramp + hold:
        return level * 0.5 * (1 + math.cos(math.pi * (u - ramp - hold) / ramp))
    return 0.0


def shock(t, t0, length, peak, freq):
    """A damped oscillation starting at t0 (pothole, collision ringing) whose
    first swing reaches peak; it decays to e^-3 by t0 + length."""
    if t < t0 or t > t0 + length:
        return 0.0
    u = t - t0
    decay = 3.0 / length
    first = math.exp(-decay * 0.25 / freq)  # envelope at the first extremum
    taper = math.sin(math.pi * min(u / (0.25 / freq), 1.0) / 2)  # no step at t0
    return peak / first * taper * math.exp(-decay * u) * math.sin(2 * math.pi * freq * u)


# --- the drives (parameters chosen with swaywatch, see sample_logs/README.md) ---

def braking_pothole(rng):
    n = int(20.0 * RATE) + 1
    vib = road(rng, n, 0.2)
    out = []
    for i in range(n):
        t = i / RATE
        a = vib[i]
        a += hann_pulse(t, 6.0, 2.0, -4.0)        # firm braking, 2 s, peak -4 m/s^2
        a += shock(t, 13.0, 0.15, -15.0, 15.0)    # pothole: +-15 m/s^2 ringing at 15 Hz
        out.append((t, a))
    return out


def hard_stop_overturn(rng):
    n = int(8.0 * RATE) + 1
    vib = road(rng, n, 0.2)
    out = []
    for i in range(n):
        t = i / RATE
        a = vib[i]
        a += plateau(t, 2.0, 0.4, 0.8, -3.0)      # emergency stop below the uplift threshold
        a += hann_pulse(t, 3.0, 0.35, -18.0)      # collision-like shock, 0.35 s, -18 m/s^2
        a += shock(t, 3.0, 0.3, 6.0, 12.0)        # structural ringing on top of it
        out.append((t, a))
    return out


def write(path, rows, sep=",", header="t_s,accel_mps2", fmt=None):
    with open(path, "w", newline="\n") as f:
        f.write(header + "\n")
        for t, a in rows:
            f.write(fmt(t, a) if fmt else "%.3f%s%.5f\n" % (t, sep, a))


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else "sample_logs"
    os.makedirs(outdir, exist_ok=True)
    rng = random.Random(SEED)
    bp = braking_pothole(rng)
    hs = hard_stop_overturn(rng)
    # Round once, so the g/ms variant holds exactly the same data.
    bp = [(round(t, 3), round(a, 5)) for t, a in bp]
    write(os.path.join(outdir, "braking-pothole.csv"), bp)
    write(os.path.join(outdir, "hard-stop-overturn.csv"), hs)
    write(os.path.join(outdir, "braking-pothole-g-ms.csv"), bp, header="time_ms;accel_g",
          fmt=lambda t, a: "%d;%.12g\n" % (round(t * 1000), a / G0))


if __name__ == "__main__":
    main()
