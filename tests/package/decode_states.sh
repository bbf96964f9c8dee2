#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# docs/examples/decode_states.py decodes every state message of a log that
# swaywatch wrote: an accel log is replayed with --publish to a file:// URL
# (an lcm-logger file), and the example must decode as many state messages
# as replay wrote state rows to --out, with no seq missing.
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
INI
"$SW" replay "$T/accel.lcmlog" --scene "$T/crate.ini" --publish "file://$T/out.lcmlog?mode=w" \
    --speed 0 --out "$T/states.csv" --quiet
rows=$(($(wc -l <"$T/states.csv") - 1))
[ "$rows" -gt 2000 ] || fail "only $rows state rows"
python3 "$SRC/docs/examples/decode_states.py" "$T/out.lcmlog" --expect "$rows" | tee "$T/decoded"
grep -q '^crate-A .* rocking' "$T/decoded" || fail "crate-A never seen rocking"
