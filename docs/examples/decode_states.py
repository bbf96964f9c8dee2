#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""decode_states.py - read an lcm-logger file and decode every state and
alarm message of swaywatch (swaywatch.state_t, swaywatch.alarm_t) with the
generated Python types.

No LCM Python module is needed (Debian has none): the event log is parsed
here by hand with struct, and the generated types decode with struct too.
Usage, as installed (/usr/local for a build installed with cmake --install):

    PYTHONPATH=/usr/share/swaywatch/lcmtypes/python python3 \\
        /usr/share/doc/swaywatch/examples/decode_states.py drive.lcmlog \\
        --channel SWAY_STATE

Each message on the channel (a regular expression, anchored as LCM's;
default SWAY_STATE; SWAY_ALARM for the alarms) is decoded as the type its
fingerprint names.  Prints one line per package and plane (states: messages, max
|theta|, min margin, phases seen; alarms: messages by kind) and the numbers
decoded.  Exit status 0; 1 if a message on the channel did not decode, a
seq number is missing, or --expect N was given and N messages were not
decoded; 2 on bad usage or an unreadable log.

Event log format (all big-endian, no header, no checksum), per event:
  uint32 sync 0xEDA1DA01, int64 eventnum, int64 timestamp (us),
  int32 channel length, int32 data length, channel bytes, data bytes.
"""
import argparse
import math
import re
import struct
import sys

from swaywatch import alarm_t, state_t

SYNC = 0xEDA1DA01
HEADER = struct.Struct(">IqqII")
PHASES = {state_t.PHASE_STUCK: "stuck", state_t.PHASE_ROCKING: "rocking",
          state_t.PHASE_OVERTURNED: "overturned"}
# alarm kinds by number, from the generated constants (KIND_UPLIFT, ...)
KINDS = {v: k[5:] for k, v in vars(alarm_t).items() if k.startswith("KIND_")}
TYPES = {state_t._get_packed_fingerprint(): state_t, alarm_t._get_packed_fingerprint(): alarm_t}


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
                    help="fail unless exactly this many messages decode")
    a = ap.parse_args()
    try:
        channel_re = re.compile(a.channel)
    except re.error as e:
        print("decode_states: --channel %s: %s" % (a.channel, e), file=sys.stderr)
        return 2

    states, alarms = {}, {}
    decoded = {state_t: 0, alarm_t: 0}
    failed = missing = 0
    last_seq = {}
    try:
        with open(a.log, "rb") as f:
            for num, _ts, channel, data in events(f):
                if not channel_re.fullmatch(channel):
                    continue
                kind = TYPES.get(data[:8])
                try:
                    if kind is None:
                        raise ValueError("not a swaywatch state_t or alarm_t (fingerprint %s)"
                                         % data[:8].hex())
                    m = kind.decode(data)
                except ValueError as e:
                    failed += 1
                    print("decode_states: event %d on %s: %s" % (num, channel, e),
                          file=sys.stderr)
                    continue
                decoded[kind] += 1
                key = (channel, kind)
                if key in last_seq and m.seq != last_seq[key] + 1:
                    missing += max(0, m.seq - last_seq[key] - 1)
                last_seq[key] = m.seq
                if kind is state_t:
                    # a package that rocks across the truck too has a state
                    # per plane: each plane its line
                    name = text(m.name)
                    if m.plane == state_t.PLANE_LATERAL:
                        name += " (sideways)"
                    p = states.setdefault(name, {
                        "count": 0, "max_theta": 0.0, "min_margin": math.inf, "phases": set()})
                    p["count"] += 1
                    p["max_theta"] = max(p["max_theta"], abs(m.theta))
                    p["min_margin"] = min(p["min_margin"], m.margin)
                    p["phases"].add(PHASES.get(m.phase, "?"))
                else:
                    name = text(m.name) or "(input)"
                    if m.plane == alarm_t.PLANE_LATERAL:
                        name += " (sideways)"
                    k = alarms.setdefault(name, {})
                    name = KINDS.get(m.kind, "KIND_%d" % m.kind)
                    k[name] = k.get(name, 0) + 1
    except (OSError, ValueError) as e:
        print("decode_states: %s: %s" % (a.log, e), file=sys.stderr)
        return 2

    for name, p in sorted(states.items()):
        print("%-16s %7d states  max|theta| %.4f rad  min margin %+.3f  %s" % (
            name, p["count"], p["max_theta"], p["min_margin"], ",".join(sorted(p["phases"]))))
    for name, k in sorted(alarms.items()):
        print("%-16s %7d alarms  %s" % (name, sum(k.values()), ", ".join(
            "%s %d" % (kind, n) for kind, n in sorted(k.items()))))
    print("decoded %d state messages and %d alarm messages on %s (%d failed, %d missing by seq)"
          % (decoded[state_t], decoded[alarm_t], a.channel, failed, missing))
    total = decoded[state_t] + decoded[alarm_t]
    if failed or missing or (a.expect is not None and total != a.expect):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
