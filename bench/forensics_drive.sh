#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# forensics_drive.sh - the time "swaywatch forensics" takes on the hour-long
# drive of issue 26 (bench/drive_log.py: a 1.3 Hz sway of 0.8 m/s^2 with
# noise, a 6 m/s^2 braking shock of 0.2 s every 10 minutes; 1 kHz): the
# crate with a frame (5.59 rad/s) and a cushion (30 rad/s) what-if, on 2
# threads, and with --no-what-if (the baseline, made alongside); wall
# and CPU time, medians of RUNS runs.  With BEFORE=BUILD_DIR also the
# what-if case by that build (BEFORE_RUNS runs, default 3), for the ratio.
# Prints the machine, the load and a Markdown table for docs/forensics.md.
#   [BEFORE=OLD_BUILD] bench/forensics_drive.sh BUILD_DIR [RUNS]
set -eu
BUILD=${1:?usage: forensics_drive.sh BUILD_DIR [RUNS]}
RUNS=${2:-5}
SRC=$(cd "$(dirname "$0")/.." && pwd)
TMP=$(mktemp -d /tmp/sw-forensics-drive.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
python3 "$SRC/bench/drive_log.py" >"$TMP/drive.csv"
CRATE=$SRC/sample_logs/crate.ini

# measure NAME SWAYWATCH N ARGS...: N runs; prints "NAME|median wall|median cpu|range"
measure() {
    name=$1
    bin=$2
    n=$3
    shift 3
    : >"$TMP/t"
    i=0
    while [ "$i" -lt "$n" ]; do
        /usr/bin/time -f "%e %U %S" -o "$TMP/one" "$bin" forensics "$TMP/drive.csv" \
            --scene "$CRATE" -q "$@" >"$TMP/out.$name" 2>/dev/null
        cat "$TMP/one" >>"$TMP/t"
        i=$((i + 1))
    done
    sed "s|^|$name $*: |" "$TMP/t" >&2 # each run (wall, user, system s), kept on stderr
    w=$(awk '{print $1}' "$TMP/t" | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
    c=$(awk '{print $2+$3}' "$TMP/t" | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
    lo=$(awk '{print $1}' "$TMP/t" | sort -n | head -1)
    hi=$(awk '{print $1}' "$TMP/t" | sort -n | tail -1)
    echo "$name|$w|$c|$lo-$hi|$n"
}

WHATIF="--frame-omega 5.59 --cushion-omega 30 --threads 2"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
{
    # shellcheck disable=SC2086
    measure whatif "$BUILD/swaywatch" "$RUNS" $WHATIF
    measure nowhatif "$BUILD/swaywatch" "$RUNS" --no-what-if --threads 2
    # shellcheck disable=SC2086
    [ -z "${BEFORE:-}" ] || measure before "$BEFORE/swaywatch" "${BEFORE_RUNS:-3}" $WHATIF
} >"$TMP/res"
same() { grep -v '^  program \|^  command ' "$1"; }
if [ -n "${BEFORE:-}" ] && [ "$(same "$TMP/out.whatif")" != "$(same "$TMP/out.before")" ]; then
    echo "WARNING: the two builds answer differently (bench/forensics_compare.sh)" >&2
fi
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //');" \
    "load before: $load_before, after: $(cut -d' ' -f1-3 /proc/loadavg); medians"
echo
echo "| case | runs | wall (s) | CPU (s) | wall, fastest-slowest (s) | wall against --no-what-if |"
echo "|---|---|---|---|---|---|"
awk -F'|' '
    { name[NR] = $1; w[NR] = $2; c[NR] = $3; r[NR] = $4; n[NR] = $5; if ($1 == "nowhatif") base = $2 }
    END {
        for (i = 1; i <= NR; i++) {
            d = "the same what-ifs, the build before"
            if (name[i] == "whatif") d = "crate, frame 5.59 rad/s, cushion 30 rad/s, 2 threads"
            if (name[i] == "nowhatif") d = "crate, --no-what-if, 2 threads"
            printf "| %s | %s | %s | %s | %s | %.1f |\n", d, n[i], w[i], c[i], r[i], w[i] / base
        }
    }' "$TMP/res"
