#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# replay_reserve.sh - what the reserve costs an offline replay of the
# hour-long drive of issue 26 (bench/drive_log.py), on the bed, the frame
# and the soft cushion of sample_logs: replay as it is (no row shows the
# reserve: the minimum alone, risk.h min_only) and with --reserve-rate 0,
# wall and CPU time, medians of RUNS runs, and the ratio to the
# --reserve-rate 0 run made alongside; then one run with every state
# evaluated (--out, every 3,600,000th row written), whose minimum the
# first must equal (EVERY=0 leaves it out); with BEFORE=BUILD_DIR also one
# default replay by that build.  CALM=1: the same drive without its shocks
# (--shock 0), where no moment stands out; MINUTES=M: a shorter drive;
# LOG=FILE.csv: another log (e.g. sw_bench gen-csv's road hour).  Prints
# the machine, the load and a Markdown table for docs/accuracy-speed.md;
# exit 1 if a minimum differs from the one with every state evaluated.
#   [CALM=1|MINUTES=M|LOG=FILE] [EVERY=0] [BEFORE=OLD_BUILD] \
#       bench/replay_reserve.sh BUILD_DIR [RUNS]
set -eu
BUILD=${1:?usage: replay_reserve.sh BUILD_DIR [RUNS]}
RUNS=${2:-5}
SRC=$(cd "$(dirname "$0")/.." && pwd)
SW=$BUILD/swaywatch
TMP=$(mktemp -d /tmp/sw-replay-reserve.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
shock=
[ -z "${CALM:-}" ] || shock="--shock 0"
if [ -n "${LOG:-}" ]; then
    ln -s "$(cd "$(dirname "$LOG")" && pwd)/$(basename "$LOG")" "$TMP/drive.csv"
else
    # shellcheck disable=SC2086
    python3 "$SRC/bench/drive_log.py" --minutes "${MINUTES:-60}" $shock >"$TMP/drive.csv"
fi

# measure SWAYWATCH N SCENE ARGS...: N runs; prints "median wall|median
# cpu|the minimum reserve, its time and the states it is over"
measure() {
    bin=$1
    n=$2
    sc=$3
    shift 3
    : >"$TMP/t"
    i=0
    while [ "$i" -lt "$n" ]; do
        /usr/bin/time -f "%e %U %S" -o "$TMP/one" "$bin" replay "$TMP/drive.csv" \
            --scene "$SRC/sample_logs/$sc.ini" --json "$@" >"$TMP/j" 2>/dev/null
        cat "$TMP/one" >>"$TMP/t"
        i=$((i + 1))
    done
    sed "s|^|$sc $*: |" "$TMP/t" >&2 # each run (wall, user, system s), kept on stderr
    w=$(awk '{print $1}' "$TMP/t" | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
    c=$(awk '{print $2+$3}' "$TMP/t" | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
    m=$(python3 -c '
import json, sys
p = json.load(open(sys.argv[1]))["packages"][0]
print("%s g at %s s (%s states)" % (p["min_reserve_g"], p["min_reserve_time"], p["reserve_evaluations"]))' "$TMP/j")
    echo "$w|$c|$m"
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for sc in crate crate-on-frame crate-on-cushion; do
    off=$(measure "$SW" "$RUNS" "$sc" --reserve-rate 0)
    min=$(measure "$SW" "$RUNS" "$sc")
    every="-|-|-"
    [ "${EVERY:-1}" = 0 ] || every=$(measure "$SW" 1 "$sc" --out "$TMP/s.csv" --every 3600000)
    before="-|-|-"
    [ -z "${BEFORE:-}" ] || before=$(measure "$BEFORE/swaywatch" 1 "$sc")
    echo "$sc|$off|$min|$every|$before"
done >"$TMP/res"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //');" \
    "load before: $load_before, after: $(cut -d' ' -f1-3 /proc/loadavg); $RUNS runs each," \
    "medians (every state, and the build before: 1 run)"
echo
echo "| scene | --reserve-rate 0: wall, CPU (s) | default (the minimum alone): wall, CPU (s) | ratio (wall) | every state (--out): wall, CPU (s) | before: wall, CPU (s) | minimum reserve |"
echo "|---|---|---|---|---|---|---|"
awk -F'|' '{
    m = $13 == "-" ? $7 : $7 "; before: " $13;
    r = $2 > 0 ? sprintf("%.2f", $5 / $2) : "-";
    printf "| %s | %s, %s | %s, %s | %s | %s, %s | %s, %s | %s |\n", $1, $2, $3, $5, $6, r, $8, $9,
        $11, $12, m }' "$TMP/res"
# the minimum alone against every state evaluated
awk -F'|' '$10 != "-" && $7 != $10 { print "DIFFERENT minimum for " $1 ": " $7 " against " $10; bad = 1 }
    END { exit bad }' "$TMP/res"
