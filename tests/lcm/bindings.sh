#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The generated Python and Java types decode a log the C types wrote, and
# LCM's Java tools (lcm-spy) find the Java types.
# usage: bindings.sh SW_LCM_TOOL PYTHON_DIR [SWAYWATCH_JAR LCM_JAR]
set -eu
TOOL=$1 PYDIR=$2
HERE=$(cd "$(dirname "$0")" && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
"$TOOL" mklog "$T/accel.lcmlog" --rate 200 --duration 1.5
PYTHONPATH="$PYDIR" python3 "$HERE/decode_log.py" "$T/accel.lcmlog" 301
if [ $# -ge 4 ]; then
    out=$(java -cp "$4:$3" "$HERE/DecodeLog.java" "$T/accel.lcmlog")
    echo "java: $out"
    [ "$out" = "decoded 301 accel_t" ]
    # lcm-spy finds message types the way LCM's class discoverer does: in
    # the jars of CLASSPATH.
    CLASSPATH="$3" java -cp "$4" lcm.util.ClassDiscoverer >"$T/classes.txt" 2>&1 || true
    for t in accel_t state_t alarm_t; do
        grep -q "class swaywatch\.$t\$" "$T/classes.txt" || { echo "no swaywatch.$t" >&2; exit 1; }
    done
fi
