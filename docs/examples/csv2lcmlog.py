#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""csv2lcmlog.py - turn a CSV acceleration log (time, longitudinal
acceleration) into an lcm-logger file of swaywatch.accel_t samples, which
lcm-logplayer can then publish on an LCM bus as if a sensor sent them: a
way to try `swaywatch monitor` and its consumers without a truck.

    PYTHONPATH=/usr/share/swaywatch/lcmtypes/python \\
        python3 csv2lcmlog.py drive.csv drive.lcmlog [--g] [--start-utime US] \\
            [--lat-col N] [--key KEYFILE] &&
        lcm-logplayer drive.lcmlog

The CSV is read as swaywatch reads it by default: column 1 time in s,
column 2 acceleration along x (forward) in m/s^2 (in g with --g), '#'
comments and a header row skipped, ',' ';' or tab delimited.  With
--lat-col N, column N (1-based, the same unit) is the acceleration across
the truck, y to the left, written to ay (else ay is 0).  Samples get
utime = start + (t - t0), t0 the first row's time, and seq 0, 1, 2, ...;
the event timestamps are the same utimes, so lcm-logplayer paces them as
they were recorded.

lcm-logplayer publishes the messages as they are in the file: it paces
them by the event timestamps but leaves their utime alone.  The monitor's
lag is the wall clock minus the sample's utime, so start is, by default,
the moment the file is written (after the CSV is read): a file played at
once, as above, shows the monitor's own delay as lag, as a live sensor
with a synchronised clock would; a file played minutes later shows those
minutes too (convert it again, or use --start-utime for fixed stamps).
Only struct is needed: no LCM Python module.

Without --key the samples are in the layout of senders without a key
(accel_v1_t), which every reader decodes.  With --key KEYFILE (a key file
of `swaywatch keygen`, which others must not be able to read) they are
accel_t signed as an authenticated sensor signs (docs/security.md): the
last key of the file, key_id its id, freshness from the wall clock in
microseconds when the file is written, +1 a sample, and mac the first 16
bytes of HMAC-SHA-256(key, channel || 0 || the 57 bytes before mac), with
Python's hmac.  A monitor given the key file (--key) takes them.
"""
import argparse
import datetime
import hashlib
import hmac
import os
import re
import stat
import struct
import sys
import time

from swaywatch import accel_t, accel_v1_t

G0 = 9.80665


def rows(path, lat):
    """Yield (line number, t, a, a_y) for every numeric row (a_y 0 without
    a lateral column: lat None, else its 0-based index)."""
    with open(path, encoding="utf-8-sig") as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = re.split(r"[,;\t]", line)
            try:
                yield n, float(fields[0]), float(fields[1]), (
                    float(fields[lat]) if lat is not None else 0.0)
            except (ValueError, IndexError):
                if n > 1 and not line[0].isalpha():
                    print("csv2lcmlog: %s:%d: skipped: %s" % (path, n, line), file=sys.stderr)


def signing_key(path):
    """(id, key) of the last key of a key file ('ID HMAC-SHA256 HEX:KEY'
    lines), refused as swaywatch refuses it."""
    mode = os.stat(path).st_mode
    if mode & (stat.S_IRWXO | stat.S_IWGRP):
        sys.exit("csv2lcmlog: %s: permissions %04o are too open: chmod 600 %s"
                 % (path, stat.S_IMODE(mode), path))
    key = None
    with open(path) as f:
        for n, line in enumerate(f, 1):
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            try:
                if len(w) != 3 or w[1].upper() != "HMAC-SHA256" or w[2][:4].upper() != "HEX:":
                    raise ValueError
                kid, secret = int(w[0]), bytes.fromhex(w[2][4:])
                if not 1 <= kid <= 255 or len(secret) != 32:
                    raise ValueError
            except ValueError:
                sys.exit("csv2lcmlog: %s:%d: not a key line 'ID HMAC-SHA256 HEX:KEY'" % (path, n))
            key = (kid, secret)
    if not key:
        sys.exit("csv2lcmlog: %s: no key in it" % path)
    return key


def encode(utime, seq, ax, ay, key, fresh, channel):
    """One sample as the sender sends it: signed with key, else the old layout."""
    if not key:
        m = accel_v1_t()
        m.utime, m.seq, m.ax, m.ay = utime, seq, ax, ay
        return m.encode()
    m = accel_t()
    m.utime, m.seq, m.ax, m.ay, m.freshness, m.key_id = utime, seq, ax, ay, fresh, key[0]
    head = m.encode()[:57]
    mac = hmac.new(key[1], channel + b"\0" + head, hashlib.sha256).digest()[:16]
    m.mac = list(struct.unpack(">16b", mac))
    return m.encode()


def iso(utime):
    """utime (us since the epoch) as ISO 8601 UTC with milliseconds."""
    t = datetime.datetime.fromtimestamp(utime // 1000000, datetime.timezone.utc)
    return "%s.%03dZ" % (t.strftime("%Y-%m-%dT%H:%M:%S"), utime % 1000000 // 1000)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv")
    ap.add_argument("out")
    ap.add_argument("--g", action="store_true", help="acceleration column in g")
    ap.add_argument("--channel", default="ACCEL")
    ap.add_argument("--start-utime", type=int, default=None,
                    help="utime of the first sample in microseconds "
                         "(default: now, when the file is written)")
    ap.add_argument("--lat-col", type=int, metavar="N",
                    help="1-based column of the lateral acceleration (y, to the left) "
                         "(default: none, ay = 0)")
    ap.add_argument("--key", metavar="KEYFILE",
                    help="sign every sample with the last key of this key file "
                         "(swaywatch keygen)")
    a = ap.parse_args()
    key = signing_key(a.key) if a.key else None

    if a.lat_col is not None and a.lat_col < 2:
        ap.error("--lat-col: a column after the time, 2 or more")
    lat = a.lat_col - 1 if a.lat_col is not None else None
    samples = [(t, acc, acc_y) for _n, t, acc, acc_y in rows(a.csv, lat)]
    if not samples:
        print("csv2lcmlog: no samples in %s" % a.csv, file=sys.stderr)
        return 1
    t0 = samples[0][0]
    scale = G0 if a.g else 1.0
    channel = a.channel.encode()
    # Stamped as late as possible: encoding and writing take milliseconds.
    start = a.start_utime if a.start_utime is not None else int(time.time() * 1e6)
    fresh = time.time_ns() // 1000  # never below what an earlier run of the key used
    out = []
    for seq, (t, acc, acc_y) in enumerate(samples):
        utime = start + int(round((t - t0) * 1e6))
        data = encode(utime, seq, acc * scale, acc_y * scale, key, fresh + seq, channel)
        out.append(struct.pack(">IqqII", 0xEDA1DA01, seq, utime, len(channel), len(data)))
        out.append(channel + data)
    with open(a.out, "wb") as f:
        f.write(b"".join(out))
    print("csv2lcmlog: %d samples written to %s, the first stamped %s%s"
          % (len(samples), a.out, iso(start), ", signed with key %d" % key[0] if key else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
