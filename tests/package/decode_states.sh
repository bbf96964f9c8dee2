#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# docs/examples/decode_states.py decodes every state message of a log that
# swaywatch wrote: an accel log is replayed with --publish to a file:// URL
# (an lcm-logger file), and the example must decode as many state messages
# as replay wrote state rows to --out, with no seq missing; on the alarm
# channel (--channel SWAY_ALARM: it gave decode errors, reading alarms as
# states) every alarm, by the name of its kind (the reserve's too).
# usage: decode_states.sh SWAYWATCH SOURCE_DIR PYTHON_TYPES_DIR
set -eu
SW=$1 SRC=$2 PYDIR=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "decode_states.sh: $*" >&2; exit 1; }
export PYTHONPATH="$PYDIR"

python3 "$SRC/tests/package/mkaccel.py" "$T/accel.lcmlog" --amplitude -5 --omega 10 --duration 2
cat >"$T/crate.ini" <<INI
[package]
name = crate-A
height = 2.0
width = 0.728
mass = 1000
[alarm]
warn_reserve_g = 2.0
critical_reserve_g = 1.0
INI
"$SW" replay "$T/accel.lcmlog" --scene "$T/crate.ini" --publish "file://$T/out.lcmlog?mode=w" \
    --speed 0 --out "$T/states.csv" --quiet
rows=$(($(wc -l <"$T/states.csv") - 1))
[ "$rows" -gt 2000 ] || fail "only $rows state rows"
python3 "$SRC/docs/examples/decode_states.py" "$T/out.lcmlog" --expect "$rows" | tee "$T/decoded"
grep -q '^crate-A .* rocking' "$T/decoded" || fail "crate-A never seen rocking"

# The alarms: as many as the log holds on SWAY_ALARM (counted here from
# the events alone), every kind named, the reserve's among them.
n=$(python3 - "$T/out.lcmlog" <<'PY'
import struct, sys
f = open(sys.argv[1], "rb")
n = 0
while (h := f.read(28)) and len(h) == 28:
    _, _, _, cl, dl = struct.unpack(">IqqII", h)
    n += f.read(cl) == b"SWAY_ALARM"
    f.read(dl)
print(n)
PY
)
[ "$n" -ge 3 ] || fail "only $n alarms in the log"
python3 "$SRC/docs/examples/decode_states.py" "$T/out.lcmlog" --channel SWAY_ALARM --expect "$n" \
    >"$T/alarms" 2>"$T/alarms.err" || { cat "$T/alarms" "$T/alarms.err"; fail "alarm channel"; }
cat "$T/alarms"
[ ! -s "$T/alarms.err" ] || { cat "$T/alarms.err"; fail "errors decoding the alarm channel"; }
grep -q '^crate-A .* alarms .*UPLIFT [0-9]' "$T/alarms" || fail "no UPLIFT alarm by name"
grep -q 'RESERVE_WARN [0-9]' "$T/alarms" || fail "no RESERVE_WARN alarm by name"
if grep -q 'KIND_\|?' "$T/alarms"; then fail "an alarm kind without its name"; fi
echo "decode_states.sh: ok"
