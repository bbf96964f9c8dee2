#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the seed corpora of the fuzz targets feed and lcmlog
(tests/fuzz/corpus/feed/, tests/fuzz/corpus/lcmlog/); their input formats
are described at the top of fuzz_feed.c and fuzz_lcmlog.c.

usage: mkseeds.py LCMTYPES_PYTHON_DIR CORPUS_DIR
  (LCMTYPES_PYTHON_DIR: build/lcmtypes/python, the generated bindings)

The seeds keep every utime and seq well inside int64: the targets
themselves reach the extremes.  The lcm-logger logs carry accel_v1_t, the
layout a sender without a key sends; the "-signed" ones accel_t, with a
freshness, a key id and a MAC (an unkeyed monitor reads both)."""
import math
import os
import struct
import sys

sys.path.insert(0, sys.argv[1])
from swaywatch import accel_t, accel_v1_t, state_t  # noqa: E402

OUT = sys.argv[2]
T0 = 1700000000000000  # us, 2023


def put(target, name, data):
    os.makedirs(os.path.join(OUT, target), exist_ok=True)
    with open(os.path.join(OUT, target, name), "wb") as f:
        f.write(data)


# ---- feed ---------------------------------------------------------------
def small(ax, ay=0.0, az=0.0):  # values selector 0: three scaled bytes
    q = lambda v, s: struct.pack(">b", max(-128, min(127, round(v / s))))
    return b"\x00" + q(ax, 0.25) + q(ay, 0.25) + q(az, 0.1)


def step(ax, az=0.0):  # kind 7: +1 ms, seq + 1
    return b"\x07" + small(ax, 0.0, az)


def pulse(n, amp=-9.0, w=10.0):
    out = b""
    for k in range(n):
        t = k * 1e-3 - 0.05
        a = amp * math.sin(w * t) if 0 <= t <= math.pi / w else 0.0
        out += step(a)
    return out


put("feed", "pulse", b"\x00" + pulse(400))
put("feed", "pulse-frame", b"\x20" + pulse(400))  # the second crate framed
put("feed", "pulse-vertical-rate", b"\x11" + pulse(200) + b"".join(step(-4, -3) for _ in range(50)))
# a jump of 30 min, confirmed by the next samples; a year ahead, refused
put("feed", "jump-confirmed",
    b"\x00" + pulse(50) + b"\x02" + struct.pack(">i", 1800000000)
    + small(0) + pulse(20) + b"\x03\x08\x06" + small(0) + pulse(20))
# any jump taken at once (max_jump < 0), with the skew check on
put("feed", "any-jump-skew", b"\x06" + pulse(30) + b"\x03\x0a\x06" + small(-2) + pulse(30)
    + b"\x03\x09\x05" + small(0) + pulse(10))
# a sensor restart: clock 60 s back, seq 0; then on
put("feed", "restart", b"\x00" + pulse(100) + b"\x06" + struct.pack(">H", 60000) + small(0)
    + pulse(100))
# duplicates, late samples, special values, timers
put("feed", "dup-late-specials",
    b"\x08" + pulse(20) + b"\x05\x05" + b"\x01" + struct.pack(">hb", -3000, 1) + small(1)
    + b"\x07\x04\x00" + b"\x07\x04\x0b" + b"\x07\x04\x13" + b"\x07\x06" + bytes(24)
    + b"\x04\x20" + pulse(20) + b"\x04\xff" + pulse(5))
# raw utime and seq: a seq far ahead (lost), then back (restart)
put("feed", "raw-seq",
    b"\x00" + pulse(10) + b"\x00" + struct.pack(">qq", T0 + 20000, 1 << 40) + small(0)
    + pulse(10) + b"\x00" + struct.pack(">qq", T0 + 40000, 3) + small(0) + pulse(10))
# utime 0 and negative (before 1970), each the first sample
put("feed", "epoch", b"\x00" + b"\x03\x04\x04" + small(0) + pulse(20))
put("feed", "before-1970", b"\x04" + b"\x03\x02\x04" + small(0) + pulse(20))


# ---- lcmlog -------------------------------------------------------------
SYNC = 0xEDA1DA01


def event(num, ts, channel, data, sync=SYNC):
    ch = channel.encode()
    return struct.pack(">IqqII", sync, num, ts, len(ch), len(data)) + ch + data


def accel(k, rate=200.0, amp=-9.0, w=10.0, signed=False):
    a = accel_t() if signed else accel_v1_t()
    if signed:
        a.freshness = T0 + k
        a.key_id = 1
        a.mac = [(7 * k + i) % 256 - 128 for i in range(16)]
    a.utime = T0 + int(k * 1e6 / rate)
    a.seq = k
    t = k / rate - 0.05
    a.ax = amp * math.sin(w * t) if 0 <= t <= math.pi / w else 0.0
    a.ay, a.az = 0.0, 0.0
    return a.utime, a.encode()


def log(n, channel="ACCEL", start=0, signed=False):
    out = b""
    for k in range(start, start + n):
        ts, d = accel(k, signed=signed)
        out += event(k, ts + 150, channel, d)
    return out


good = log(120)
put("lcmlog", "pulse", b"\x00" + good)
put("lcmlog", "pulse-strict-skew", b"\x09" + good)
put("lcmlog", "truncated", b"\x00" + good[: len(good) - 37])
# event 10's data length past the end of the file; then the rest of the log
# (a length of gigabytes takes the same path, but LCM's reader allocates it)
e = len(event(0, 0, "ACCEL", accel(0)[1]))
bad_len = bytearray(good)
bad_len[10 * e + 24:10 * e + 28] = struct.pack(">I", 100000)
put("lcmlog", "bad-length", b"\x00" + bytes(bad_len))
put("lcmlog", "bad-length-strict", b"\x01" + bytes(bad_len))
bad_sync = bytearray(good)
bad_sync[20 * e] ^= 0xFF
put("lcmlog", "bad-sync", b"\x00" + bytes(bad_sync))
put("lcmlog", "junk-between", b"\x00" + good[: 30 * e] + b"\xde\xad\xbe\xef" * 9 + good[30 * e:])
# other channels interleaved; a regex taking them all; a state_t on ACCEL
st = state_t()
st.utime = T0
mixed = b""
for k in range(60):
    ts, d = accel(k)
    mixed += event(2 * k, ts, "ACCEL", d) + event(2 * k + 1, ts, "SWAY_STATE", st.encode())
mixed += event(200, T0 + 400000, "ACCEL", st.encode()) + event(201, T0 + 401000, "ACCEL", b"\x00" * 5)
put("lcmlog", "mixed-channels", b"\x00" + mixed)
put("lcmlog", "mixed-channels-regex", b"\x02" + mixed)
put("lcmlog", "no-such-channel", b"\x04" + mixed)
# hostile length fields (tests/lcm/lcmlog_hostile.sh): event 10 of 20 with
# its channel or data length beyond the file, past LCM's 256 MB limit,
# negative or zero; each one corrupted region, the events after it read
short = log(20)
e20 = len(short) // 20
for name, off, value in [("data-7fffffff", 24, 0x7FFFFFFF), ("chan-7fffffff", 20, 0x7FFFFFFF),
                         ("data-negative", 24, 0x80000000), ("chan-zero", 20, 0),
                         ("data-256m", 24, 0x0FFFFFF0)]:
    bad = bytearray(short)
    struct.pack_into(">I", bad, 10 * e20 + off, value)
    put("lcmlog", "hostile-" + name, b"\x00" + bytes(bad))
put("lcmlog", "pulse-signed", b"\x00" + log(60, signed=True))
put("lcmlog", "empty", b"\x00")
put("lcmlog", "not-a-log", b"\x00" + b"t,a\n0,0\n0.001,-1\n")
