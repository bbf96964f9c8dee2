#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Stands in for systemd's notification socket (sd_notify(3)) in the tests:
binds a datagram socket at PATH and writes every message received to OUT,
one line each: the seconds since it started, then the message with its
newlines as '|'.  Creates READY_FILE once it listens; stops after SECONDS
without a message, or on SIGTERM.

usage: notify_recv.py PATH OUT READY_FILE SECONDS"""
import os
import signal
import socket
import sys
import time

path, out, ready, idle = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
s.bind(path)
s.settimeout(idle)
t0 = time.monotonic()
with open(out, "w", buffering=1) as f:
    open(ready, "w").close()
    try:
        while True:
            msg = s.recv(4096).decode("utf-8", "replace")
            f.write("%.3f %s\n" % (time.monotonic() - t0, msg.replace("\n", "|")))
    except socket.timeout:
        pass
os.unlink(path)
