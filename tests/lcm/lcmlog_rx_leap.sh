#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Times on the source's clock: in an lcm-logger file whose receive times
# (lcm-logger's own stamps) leap ahead - 8e9 s, or 20 s - where the
# samples' utimes have a 10 ms hole, the crate's overturn is reported at
# its time in the 5 s drive, the log is not taken for one spanning 92000
# days, and replay --publish --speed 1 is not paused for the leap.  It
# used to print "OVERTURNED at 8000000003 s" (with --force) and sleep 20 s.
# usage: lcmlog_rx_leap.sh SWAYWATCH SW_LCM_TOOL SCENE
set -eu
SW=$1 TOOL=$2 SCENE=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}

# 5 s at 1 kHz; a braking of 12 m/s^2 at 8 rad/s from 1 s overturns the crate.
"$TOOL" mklog "$T/drive.lcmlog" --rate 1000 --duration 5 --amplitude -12 --omega 8 --lead 1
"$SW" replay "$T/drive.lcmlog" --scene "$SCENE" --settle 0 --json >"$T/plain.json" 2>"$T/err" ||
    fail "the drive as recorded"
for leap in 8000000000 20; do
    python3 - "$T/drive.lcmlog" "$T/leap.lcmlog" "$leap" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
ev = 81  # 28 bytes of header, "ACCEL", a 48-byte accel_t
out = bytearray()
for k in range(len(data) // ev):
    if 2490 <= k < 2500:
        continue  # a 10 ms hole in the samples
    e = bytearray(data[k * ev:(k + 1) * ev])
    if k >= 2500:  # lcm-logger's receive time leaps
        ts = struct.unpack_from(">q", e, 12)[0]
        struct.pack_into(">q", e, 12, ts + int(sys.argv[3]) * 1000000)
    out += e
open(sys.argv[2], "wb").write(bytes(out))
PY
    "$SW" replay "$T/leap.lcmlog" --scene "$SCENE" --settle 0 --json >"$T/out.json" 2>"$T/err" ||
        fail "leap $leap s: replay refused the log"
    python3 - "$T/plain.json" "$T/out.json" <<'PY' || fail "leap $leap s: times not on the source's clock"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
pa, pb = a["packages"][0], b["packages"][0]
assert pa["overturned"] and pb["overturned"], (pa["overturned"], pb["overturned"])
assert abs(pa["overturn_time"] - pb["overturn_time"]) < 0.05, (pa["overturn_time"], pb["overturn_time"])
assert b["input"]["duration"] < 6.0, b["input"]["duration"]
PY
done
# --publish --speed 1 paces 5 s of samples; the 20 s leap must not add to it
start=$(date +%s)
rc=0
timeout 15 "$SW" replay "$T/leap.lcmlog" --scene "$SCENE" --settle 0 --speed 1 \
    --publish "file://$T/out.lcmlog?mode=w" >/dev/null 2>"$T/err" || rc=$?
[ "$rc" -eq 0 ] || fail "replay --publish --speed 1: exit $rc (124: paused for the leap)"
took=$(($(date +%s) - start))
[ "$took" -le 12 ] || fail "replay --publish --speed 1 took $took s for 5 s of samples"
echo "ok"
