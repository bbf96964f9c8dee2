#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Decode the accel_t messages of an lcm-logger file with the generated
Python types alone (no 'lcm' Python module: Debian has none).  Usage:
decode_log.py LOG EXPECTED_COUNT; exits non-zero on any surprise."""
import math
import struct
import sys

from swaywatch import accel_t

SYNC = 0xEDA1DA01


def events(path):
    """(eventnum, timestamp_us, channel, data) for every event of the log."""
    with open(path, "rb") as f:
        while True:
            hdr = f.read(28)
            if len(hdr) < 28:
                return
            sync, num, ts, clen, dlen = struct.unpack(">IqqII", hdr)
            if sync != SYNC:
                raise ValueError("bad sync word at event %d" % num)
            yield num, ts, f.read(clen).decode(), f.read(dlen)


def main():
    path, expected = sys.argv[1], int(sys.argv[2])
    n, last = 0, None
    for _, ts, channel, data in events(path):
        if channel != "ACCEL":
            continue
        m = accel_t.decode(data)
        assert m.seq == n, (m.seq, n)
        assert m.utime == ts, "sample time is the log time in this log"
        assert last is None or m.utime > last
        assert all(math.isfinite(v) for v in (m.ax, m.ay, m.az))
        last = m.utime
        n += 1
    try:
        accel_t.decode(b"\0" * 48)
        raise AssertionError("a wrong fingerprint must be refused")
    except ValueError:
        pass
    if n != expected:
        sys.exit("decoded %d accel_t, expected %d" % (n, expected))
    print("decoded %d accel_t" % n)


main()
