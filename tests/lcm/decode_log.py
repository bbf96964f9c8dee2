#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Decode the accel samples of an lcm-logger file with the generated
Python types alone (no 'lcm' Python module: Debian has none).  Usage:

    decode_log.py LOG EXPECTED_COUNT                 samples of a sender without a key
    decode_log.py LOG EXPECTED_COUNT --key KEYFILE   signed samples

Without a key the samples must be accel_v1_t, the layout every reader
decodes (OLD_TYPES=DIR: also with the accel_t that lcm-gen makes from
swaywatch 0.1.0's file, and the new accel_t must refuse them).  With a key
they must be accel_t, signed with the key file's last key: each MAC is
computed here with Python's hmac and hashlib from the key file and the
message's bytes as docs/lcm.md states them, independently of the C code
(libsodium) that wrote them, and the freshness must rise by one a sample.
Exits non-zero on any surprise."""
import hashlib
import hmac
import importlib.util
import math
import os
import struct
import sys

from swaywatch import accel_t, accel_v1_t

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


def last_key(path):
    """(id, key bytes) of the last key line of a key file."""
    found = None
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            assert len(w) == 3 and w[1].upper() == "HMAC-SHA256" and w[2][:4].upper() == "HEX:", line
            found = (int(w[0]), bytes.fromhex(w[2][4:]))
    assert found and len(found[1]) == 32
    return found


def old_accel_t():
    """accel_t of swaywatch 0.1.0, generated from its file, or None."""
    d = os.environ.get("OLD_TYPES")
    if not d:
        return None
    spec = importlib.util.spec_from_file_location("old_accel_t", os.path.join(d, "swaywatch",
                                                                             "accel_t.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.accel_t


def refused(cls, data):
    try:
        cls.decode(data)
    except (ValueError, struct.error):
        return True
    return False


def main():
    path, expected = sys.argv[1], int(sys.argv[2])
    key = last_key(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[3] == "--key" else None
    old = old_accel_t()
    n, last, fresh = 0, None, None
    for _, ts, channel, data in events(path):
        if channel != "ACCEL":
            continue
        if key:
            assert len(data) == 73, len(data)
            m = accel_t.decode(data)
            assert refused(accel_v1_t, data), "the old layout's decoder must refuse accel_t"
            kid, k = key
            assert m.key_id == kid, (m.key_id, kid)
            want = hmac.new(k, channel.encode() + b"\0" + data[:57], hashlib.sha256).digest()[:16]
            got = struct.pack(">16b", *m.mac)
            assert got == data[57:73]
            assert hmac.compare_digest(want, got), "sample %d: MAC %s, expected %s" % (
                n, got.hex(), want.hex())
            assert fresh is None or m.freshness == fresh + 1, (m.freshness, fresh)
            fresh = m.freshness
        else:
            assert len(data) == 48, len(data)
            m = accel_v1_t.decode(data)
            assert refused(accel_t, data), "accel_t's decoder must refuse the old layout"
            if old:
                o = old.decode(data)  # a reader built from 0.1.0 reads it
                assert (o.utime, o.seq, o.ax, o.ay, o.az) == (m.utime, m.seq, m.ax, m.ay, m.az)
        assert m.seq == n, (m.seq, n)
        assert m.utime == ts, "sample time is the log time in this log"
        assert last is None or m.utime > last
        assert all(math.isfinite(v) for v in (m.ax, m.ay, m.az))
        last = m.utime
        n += 1
    for cls in (accel_t, accel_v1_t):
        assert refused(cls, b"\0" * 73), "a wrong fingerprint must be refused"
    if n != expected:
        sys.exit("decoded %d accel samples, expected %d" % (n, expected))
    print("decoded %d %s" % (n, "signed accel_t" if key else "accel_v1_t"))


main()
