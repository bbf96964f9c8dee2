#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""csv2lcmlog.py - turn a CSV acceleration log (time, longitudinal
acceleration) into an lcm-logger file of swaywatch.accel_t samples, which
lcm-logplayer can then publish on an LCM bus as if a sensor sent them: a
way to try `swaywatch monitor` and its consumers without a truck.

    PYTHONPATH=/usr/share/swaywatch/lcmtypes/python \\
        python3 csv2lcmlog.py drive.csv drive.lcmlog [--g] [--start-utime US] &&
        lcm-logplayer drive.lcmlog

The CSV is read as swaywatch reads it by default: column 1 time in s,
column 2 acceleration along x (forward) in m/s^2 (in g with --g), '#'
comments and a header row skipped, ',' ';' or tab delimited.  Samples get
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
"""
import argparse
import datetime
import re
import struct
import sys
import time

from swaywatch import accel_t

G0 = 9.80665


def rows(path):
    """Yield (line number, t, a) for every numeric row."""
    with open(path, encoding="utf-8-sig") as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = re.split(r"[,;\t]", line)
            try:
                yield n, float(fields[0]), float(fields[1])
            except (ValueError, IndexError):
                if n > 1 and not line[0].isalpha():
                    print("csv2lcmlog: %s:%d: skipped: %s" % (path, n, line), file=sys.stderr)


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
    a = ap.parse_args()

    samples = [(t, acc) for _n, t, acc in rows(a.csv)]
    if not samples:
        print("csv2lcmlog: no samples in %s" % a.csv, file=sys.stderr)
        return 1
    t0 = samples[0][0]
    scale = G0 if a.g else 1.0
    channel = a.channel.encode()
    # Stamped as late as possible: encoding and writing take milliseconds.
    start = a.start_utime if a.start_utime is not None else int(time.time() * 1e6)
    out = []
    for seq, (t, acc) in enumerate(samples):
        m = accel_t()
        m.utime = start + int(round((t - t0) * 1e6))
        m.seq = seq
        m.ax = acc * scale
        data = m.encode()
        out.append(struct.pack(">IqqII", 0xEDA1DA01, seq, m.utime, len(channel), len(data)))
        out.append(channel + data)
    with open(a.out, "wb") as f:
        f.write(b"".join(out))
    print("csv2lcmlog: %d samples written to %s, the first stamped %s"
          % (len(samples), a.out, iso(start)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
