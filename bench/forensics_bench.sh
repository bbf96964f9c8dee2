#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# forensics_bench.sh - the time "swaywatch forensics" takes on the
# investigator's case of issue 17: an hour-long 1 kHz log (sw_bench gen-csv
# --incident: calm driving ending in a hard stop), one crate, a frame
# what-if and a cushion what-if; wall and CPU time, median of RUNS runs,
# on 1 thread (the baseline, measured in the same run) and on 2; the
# default catalogue (four supports) on 2 threads too (CATALOGUE=1).  Prints a Markdown
# table for docs/forensics.md.
#   bench/forensics_bench.sh BUILD_DIR [RUNS]
set -eu
BUILD=${1:?usage: forensics_bench.sh BUILD_DIR [RUNS]}
RUNS=${2:-3}
SRC=$(cd "$(dirname "$0")/.." && pwd)
SW=$BUILD/swaywatch
TMP=$(mktemp -d /tmp/sw-forensics-bench.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
"$BUILD/bench/sw_bench" gen-csv --hours 1 --incident >"$TMP/incident.csv"
CRATE=$SRC/sample_logs/crate.ini

# measure NAME ARGS...: RUNS runs; prints "NAME|median wall|median cpu"
measure() {
    name=$1
    shift
    : >"$TMP/t"
    i=0
    while [ "$i" -lt "$RUNS" ]; do
        /usr/bin/time -f "%e %U %S" -o "$TMP/one" "$SW" forensics "$TMP/incident.csv" \
            --scene "$CRATE" -q "$@" >"$TMP/out.$name" 2>/dev/null
        cat "$TMP/one" >>"$TMP/t"
        i=$((i + 1))
    done
    w=$(awk '{print $1}' "$TMP/t" | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
    c=$(awk '{print $2+$3}' "$TMP/t" | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
    echo "$name|$w|$c"
}

{
    measure t1 --frame-omega 1Hz --cushion-omega 8Hz --threads 1
    measure t2 --frame-omega 1Hz --cushion-omega 8Hz --threads 2
    [ -z "${CATALOGUE:-}" ] || measure cat2 --threads 2
} >"$TMP/res"
cmp -s "$TMP/out.t1" "$TMP/out.t2" || echo "WARNING: 1 and 2 threads answer differently" >&2
w1=$(awk -F'|' '$1=="t1"{print $2}' "$TMP/res")
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //');" \
    "load before: $(cut -d' ' -f1-3 /proc/loadavg); $RUNS runs each, medians"
echo
echo "| case | threads | wall (s) | CPU (s) | speed-up against 1 thread |"
echo "|---|---|---|---|---|"
awk -F'|' -v w1="$w1" '{
    c = $1 == "cat2" ? "crate, the catalogue (4 supports)" : "crate, frame 1 Hz, cushion 8 Hz";
    t = $1 == "t1" ? 1 : 2;
    s = $1 == "cat2" ? "-" : sprintf("%.2f", w1 / $2);
    printf "| %s | %d | %s | %s | %s |\n", c, t, $2, $3, s }' "$TMP/res"
