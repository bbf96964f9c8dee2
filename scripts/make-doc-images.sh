#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Make the pictures of README.md (docs/img/) by running the commands its
# walkthrough shows: the figure of a replay (replay --plot), a terminal
# capture of the live monitor on loopback, the boundary plot.  Needs a build (BUILD,
# default build) with LCM; the monitor part runs in a private network
# namespace (root or user namespaces), as the README's loopback set-up.
# usage: scripts/make-doc-images.sh [replay|monitor|boundary]...
set -eu
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${BUILD:-build}
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
SW=$BUILD/swaywatch
OUT=${OUT:-$ROOT/docs/img} # where the pictures go (the tests: a scratch folder)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p "$OUT"
[ -x "$SW" ] || { echo "make-doc-images.sh: no $SW: build first" >&2; exit 1; }

replay() {
    "$SW" replay sample_logs/braking-pothole.csv --scene sample_logs/crate.ini \
        --scene sample_logs/crate-on-frame.ini --plot "$OUT/replay.png" --quiet
    echo "make-doc-images.sh: $OUT/replay.png"
}

# The live monitor on loopback, as a terminal shows it: a CSV drive made
# into an lcm-logger file, played by lcm-logplayer at real time into the
# monitor, its alarms printed by the example listener.
monitor() {
    if [ -z "${SW_IN_NETNS:-}" ] && ! ip route get 239.255.76.67 >/dev/null 2>&1; then
        SW_IN_NETNS=1 exec unshare -n sh "$0" monitor
    fi
    if [ -n "${SW_IN_NETNS:-}" ]; then
        ip link set lo up
        ip route add 224.0.0.0/4 dev lo
    fi
    LISTENER=$BUILD/docs/examples/sw_example_alarm_listener
    export PYTHONPATH="$BUILD/lcmtypes/python"
    "$SW" monitor --scene sample_logs/crate.ini --scene sample_logs/crate-on-frame.ini \
        --status 2 2>"$T/monitor.txt" &
    mon=$!
    "$LISTENER" 2>/dev/null >"$T/alarms.txt" &
    lis=$!
    # As the README does it: converted (samples stamped from now) and played
    # at once, so the monitor's lag is what a user following it sees.
    sleep 0.5
    python3 docs/examples/csv2lcmlog.py sample_logs/hard-stop-overturn.csv "$T/drive.lcmlog" \
        >"$T/convert.txt" &&
        lcm-logplayer "$T/drive.lcmlog" >/dev/null
    # The sensor's silence after the drive is an alarm; stop once the
    # monitor has said it (a loaded machine may lag the drive), not after
    # a fixed time, so that the picture does not depend on the load.
    i=0
    while [ $i -lt 100 ] && ! grep -q 'kind=sensor_gap' "$T/monitor.txt"; do
        sleep 0.1
        i=$((i + 1))
    done
    sleep 0.2
    kill -INT "$mon"
    wait "$mon" || true
    kill -INT "$lis"
    wait "$lis" || true
    {
        echo '$ swaywatch monitor --scene sample_logs/crate.ini --scene sample_logs/crate-on-frame.ini --status 2 &'
        echo '$ alarm_listener &            # docs/examples/alarm_listener.c'
        echo '$ python3 docs/examples/csv2lcmlog.py sample_logs/hard-stop-overturn.csv drive.lcmlog &&'
        echo '>     lcm-logplayer drive.lcmlog  # the "sensor": 8 s of a hard stop, in real time'
        sed "s|$T/||g" "$T/convert.txt"
        # Interleave by order of appearance is lost between two processes:
        # the monitor's lines, then the alarms.
        sed "s|$ROOT/||g" "$T/monitor.txt"
        echo '$ # what alarm_listener printed:'
        cat "$T/alarms.txt"
    } >"$OUT/monitor.txt"
    echo "make-doc-images.sh: $OUT/monitor.txt"
}

# The lowest half-sine braking pulse that overturns each crate, in g,
# against its duration (the boundary command draws it with gnuplot).
boundary() {
    "$SW" boundary --scene sample_logs/crate.ini --scene sample_logs/crate-on-frame.ini \
        --pulse half-sine --pulse-duration 100ms:1500ms:50ms --out "$T/boundary.csv" --quiet \
        --title "swaywatch boundary: half-sine pulse, the crate on the bed and on a frame" \
        --plot "$OUT/boundary.png"
    echo "make-doc-images.sh: $OUT/boundary.png"
}

[ $# -gt 0 ] || set -- replay monitor boundary
for what in "$@"; do
    "$what"
done
