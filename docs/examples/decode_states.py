#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""decode_states.py - read an lcm-logger file and decode every state message
of swaywatch (swaywatch.state_t) with the generated Python types.

No LCM Python module is needed (Debian has none): the event log is parsed
here by hand with struct, and the generated types decode with struct too.

    PYTHONPATH=/usr/share/swaywatch/lcmtypes/python \\
        python3 decode_states.py drive.lcmlog [--channel SWAY_STATE] [--expect N]

Prints one line per package (messages, max |theta|, min margin, phases
seen) and the number decoded.  Exit status 0; 1 if a message on the state
channel did not decode, a seq number is missing, or --expect N was given and
N messages were not decoded; 2 on bad usage or an unreadable log.

Event log format (all big-endian, no header, no checksum), per event:
  uint32 sync 0xEDA1DA01, int64 eventnum, int64 timestamp (us),
  int32 channel length, int32 data length, channel bytes, data bytes.
"""
import argparse
import math
import struct
import sys

from swaywatch import state_t

SYNC = 0xEDA1DA01
HEADER = struct.Struct(">IqqII")
PHASES = {state_t.PHASE_STUCK: "stuck", state_t.PHASE_ROCKING: "rocking",
          state_t.PHASE_OVERTURNED: "overturned"}


def events(f):
    """Yield (eventnum, timestamp_us, channel, data) from an open log."""
    while True:
        hdr = f.read(HEADER.size)
        if not hdr:
            return
        if len(hdr) < HEADER.size:
            raise ValueError("log truncated inside an event header")
        sync, num, ts, clen, dlen = HEADER.unpack(hdr)
        if sync != SYNC:
            raise ValueError("no sync word at event %d" % num)
        channel = f.read(clen)
        data = f.read(dlen)
        if len(channel) < clen or len(data) < dlen:
            raise ValueError("log truncated inside event %d" % num)
        yield num, ts, channel.decode("utf-8", "replace"), data


def text(int8s):
    """A NUL-padded int8_t[] of the message as a str."""
    raw = bytes(b & 0xFF for b in int8s)
    return raw.split(b"\0", 1)[0].decode("utf-8", "replace")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("log")
    ap.add_argument("--channel", default="SWAY_STATE")
    ap.add_argument("--expect", type=int, default=None,
                    help="fail unless exactly this many state messages decode")
    a = ap.parse_args()

    packages = {}
    decoded = failed = missing = 0
    last_seq = None
    try:
        with open(a.log, "rb") as f:
            for _num, _ts, channel, data in events(f):
                if channel != a.channel:
                    continue
                try:
                    m = state_t.decode(data)
                except ValueError as e:
                    failed += 1
                    print("decode_states: event %d: %s" % (_num, e), file=sys.stderr)
                    continue
                decoded += 1
                if last_seq is not None and m.seq != last_seq + 1:
                    missing += max(0, m.seq - last_seq - 1)
                last_seq = m.seq
                p = packages.setdefault(text(m.name), {
                    "count": 0, "max_theta": 0.0, "min_margin": math.inf, "phases": set()})
                p["count"] += 1
                p["max_theta"] = max(p["max_theta"], abs(m.theta))
                p["min_margin"] = min(p["min_margin"], m.margin)
                p["phases"].add(PHASES.get(m.phase, "?"))
    except (OSError, ValueError) as e:
        print("decode_states: %s: %s" % (a.log, e), file=sys.stderr)
        return 2

    for name, p in sorted(packages.items()):
        print("%-16s %7d states  max|theta| %.4f rad  min margin %+.3f  %s" % (
            name, p["count"], p["max_theta"], p["min_margin"], ",".join(sorted(p["phases"]))))
    print("decoded %d state messages on %s (%d failed, %d missing by seq)" % (
        decoded, a.channel, failed, missing))
    if failed or missing or (a.expect is not None and decoded != a.expect):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
