#!/usr/bin/env python3
"""csv2lcmlog.py - turn a CSV acceleration log (time, longitudinal
acceleration) into an lcm-logger file of swaywatch.accel_t samples, which
lcm-logplayer can then publish on an LCM bus as if a sensor sent them: a
way to try `swaywatch monitor` and its consumers without a truck.

    PYTHONPATH=/usr/share/swaywatch/lcmtypes/python \\
        python3 csv2lcmlog.py drive.csv drive.lcmlog [--g] [--start-utime US]
    lcm-logplayer drive.lcmlog

The CSV is read as swaywatch reads it by default: column 1 time in s,
column 2 acceleration along x (forward) in m/s^2 (in g with --g), '#'
comments and a header row skipped, ',' ';' or tab delimited.  Samples get
utime = start + t (start: now, or --start-utime) and seq 0, 1, 2, ...; the
event timestamps are the same utimes, so lcm-logplayer paces them as they
were recorded.  Only struct is needed: no LCM Python module.
"""
import argparse
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv")
    ap.add_argument("out")
    ap.add_argument("--g", action="store_true", help="acceleration column in g")
    ap.add_argument("--channel", default="ACCEL")
    ap.add_argument("--start-utime", type=int, default=None,
                    help="utime of t = 0 in microseconds (default: now)")
    a = ap.parse_args()

    start = a.start_utime if a.start_utime is not None else int(time.time() * 1e6)
    scale = G0 if a.g else 1.0
    channel = a.channel.encode()
    count = 0
    with open(a.out, "wb") as out:
        for _n, t, acc in rows(a.csv):
            m = accel_t()
            m.utime = start + int(round(t * 1e6))
            m.seq = count
            m.ax = acc * scale
            data = m.encode()
            out.write(struct.pack(">IqqII", 0xEDA1DA01, count, m.utime, len(channel), len(data)))
            out.write(channel + data)
            count += 1
    print("csv2lcmlog: %d samples written to %s" % (count, a.out))
    return 0 if count else 1


if __name__ == "__main__":
    sys.exit(main())
