#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# replay_planes.sh - what the lateral plane costs the hour-long replay of
# bench/drive_log.py's drive (issue 29): the three sample scenes as they
# are, on the drive as it is (one plane), against the same scenes with a
# depth equal to their width on the same drive with a lateral column that
# repeats the longitudinal one (two planes, the second the first's twin:
# the same work twice, and the same answers, which the script checks).
# Each with --reserve-rate 0 and as it is (the smallest reserve alone),
# CPU and wall time, medians of RUNS runs taken in turn; the ratio of the
# default replay to --reserve-rate 0 (the replay bench's goal: 2 on the
# bed and the frame, 3 on the cushion) and of two planes to one.  Prints
# the machine, the load and a Markdown table for docs/accuracy-speed.md;
# exit 1 if a lateral plane's answer differs from its longitudinal twin's.
#   [MINUTES=M] bench/replay_planes.sh BUILD_DIR [RUNS]
set -eu
BUILD=${1:?usage: replay_planes.sh BUILD_DIR [RUNS]}
RUNS=${2:-5}
SRC=$(cd "$(dirname "$0")/.." && pwd)
SW=$BUILD/swaywatch
TMP=$(mktemp -d /tmp/sw-replay-planes.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
python3 "$SRC/bench/drive_log.py" --minutes "${MINUTES:-60}" >"$TMP/one.csv"
awk -F, 'NR == 1 { print $0 ",lat_accel_ms2"; next } { print $0 "," $2 }' "$TMP/one.csv" \
    >"$TMP/two.csv"

# one SCENE PLANES MODE: one replay (MODE off: --reserve-rate 0; default:
# as it is); appends "wall cpu" to $TMP/t.SCENE.PLANES.MODE, its JSON in
# $TMP/j.SCENE.PLANES.MODE
one() {
    sc=$1
    p=$2
    mode=$3
    if [ "$p" = 1 ]; then
        set -- "$TMP/one.csv" --scene "$SRC/sample_logs/$sc.ini"
    else
        set -- "$TMP/two.csv" --scene "$TMP/$sc.ini" --lat-col lat_accel_ms2
    fi
    [ "$mode" = default ] || set -- "$@" --reserve-rate 0
    /usr/bin/time -f "%e %U %S" -o "$TMP/tm" "$SW" replay "$@" --json >"$TMP/j.$sc.$p.$mode" \
        2>/dev/null
    awk '{ print $1, $2 + $3 }' "$TMP/tm" >>"$TMP/t.$sc.$p.$mode"
}
med() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for sc in crate crate-on-frame crate-on-cushion; do
    # the scene with a depth equal to its width: the lateral plane is the other's twin
    sed 's/^\(width *= *\)\([0-9.]*\)\(.*\)/&\ndepth = \2/' "$SRC/sample_logs/$sc.ini" \
        >"$TMP/$sc.ini"
    i=0
    while [ "$i" -lt "$RUNS" ]; do # in turn, so that all four see the same load
        for p in 1 2; do
            for mode in off default; do one "$sc" "$p" "$mode"; done
        done
        i=$((i + 1))
    done
    # the twin answers as the longitudinal plane and as the planar run
    for mode in off default; do
        python3 - "$TMP/j.$sc.2.$mode" "$TMP/j.$sc.1.$mode" <<'PY' || exit 1
import json, sys
two = json.load(open(sys.argv[1]))["packages"][0]
one = json.load(open(sys.argv[2]))["packages"][0]
lat = two["lateral"]
for k in ("overturned", "max_theta_ratio", "min_margin", "min_reserve_g"):
    assert lat[k] == one[k] == two[k], (sys.argv[1], k, lat[k], one[k], two[k])
PY
    done
    r=$(python3 -c '
import json, sys
p = json.load(open(sys.argv[1]))["packages"][0]
print("%s g at %s s" % (p["min_reserve_g"], p["min_reserve_time"]))' "$TMP/j.$sc.1.default")
    row="$sc"
    for f in 1.off 1.default 2.off 2.default; do
        row="$row|$(cut -d' ' -f1 "$TMP/t.$sc.$f" | med)|$(cut -d' ' -f2 "$TMP/t.$sc.$f" | med)"
    done
    echo "$row|$r"
done >"$TMP/res"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //');" \
    "load before: $load_before, after: $(cut -d' ' -f1-3 /proc/loadavg); uptime: $(uptime);" \
    "$RUNS runs each, medians"
echo
echo "| scene | one plane, --reserve-rate 0: wall, CPU (s) | one plane, default: wall, CPU (s) | ratio (CPU) | two planes, --reserve-rate 0: wall, CPU (s) | two planes, default: wall, CPU (s) | ratio (CPU) | two / one (CPU), --reserve-rate 0 / default | minimum reserve (each plane) |"
echo "|---|---|---|---|---|---|---|---|---|"
awk -F'|' '{
    printf "| %s | %s, %s | %s, %s | %.2f | %s, %s | %s, %s | %.2f | %.2f / %.2f | %s |\n", $1,
        $2, $3, $4, $5, $5 / $3, $6, $7, $8, $9, $9 / $7, $7 / $3, $9 / $5, $10 }' "$TMP/res"
