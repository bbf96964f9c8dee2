#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# docs/examples/csv2lcmlog.py: a CSV drive converted to an lcm-logger file
# replays to the same result as the CSV itself.
# usage: csv2lcmlog.sh SWAYWATCH SOURCE_DIR PYTHON_TYPES_DIR
set -eu
SW=$1 SRC=$2 PYDIR=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "csv2lcmlog.sh: $*" >&2; exit 1; }
export PYTHONPATH="$PYDIR"

# 4 s at 1 kHz in g, with a header and a comment: a hard stop (-1.2 g
# half-sine of 10 rad/s at 0.5 s) that overturns the crate.
python3 - >"$T/drive.csv" <<'PY'
import math
print("# hard stop, 1 kHz\ntime,ax_g")
for i in range(4001):
    t = i / 1000
    a = -1.2 * math.sin(10 * (t - 0.5)) if 0.5 <= t <= 0.5 + math.pi / 10 else 0.0
    print("%.3f,%.6f" % (t, a))
PY
printf '[package]\nname = crate-A\nheight = 2.0\nwidth = 0.728\nmass = 1000\n' >"$T/crate.ini"
python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/drive.csv" "$T/drive.lcmlog" --g \
    --start-utime 1700000000000000
"$SW" replay "$T/drive.csv" --scene "$T/crate.ini" --accel-unit g --json >"$T/csv.json"
"$SW" replay "$T/drive.lcmlog" --scene "$T/crate.ini" --json >"$T/lcm.json" 2>/dev/null
python3 - "$T/csv.json" "$T/lcm.json" <<'PY' || fail "the two replays differ"
import json, sys
a, b = (json.load(open(p))["packages"][0] for p in sys.argv[1:3])
print("csv:    overturned %s at %s, max|theta| %s" % (a["overturned"], a["overturn_time"], a["max_abs_theta"]))
print("lcmlog: overturned %s at %s, max|theta| %s" % (b["overturned"], b["overturn_time"], b["max_abs_theta"]))
assert a["overturned"] and b["overturned"]
assert a["samples_read"] == b["samples_read"] == 4001
assert abs(a["overturn_time"] - b["overturn_time"]) < 1e-6
assert abs(a["uplift_time"] - b["uplift_time"]) < 1e-6
PY

# Without --start-utime the first sample is stamped with the time the file
# is written, and the others follow it by their CSV time: played at once,
# the stamps are those of a live sensor (the monitor's lag stays its own).
before=$(python3 -c 'import time; print(int(time.time() * 1e6))')
python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/drive.csv" "$T/now.lcmlog" --g >/dev/null
python3 - "$T/now.lcmlog" "$before" <<'PY' || fail "default stamps are not the time of writing"
import struct, sys, time
from swaywatch import accel_v1_t  # without --key: the layout every reader decodes
after = int(time.time() * 1e6)
f = open(sys.argv[1], "rb")
u = []
while (h := f.read(28)) and len(h) == 28:
    _, _, ts, cl, dl = struct.unpack(">IqqII", h)
    f.read(cl)
    m = accel_v1_t.decode(f.read(dl))
    assert m.utime == ts, (m.utime, ts)
    u.append(m.utime)
print("default start: %.3f s after the converter started, %.3f s before it ended"
      % ((u[0] - int(sys.argv[2])) / 1e6, (after - u[0]) / 1e6))
assert int(sys.argv[2]) <= u[0] <= after
assert len(u) == 4001 and u[-1] - u[0] == 4000000
PY
