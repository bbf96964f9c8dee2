#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs lcm_latency against `swaywatch monitor` and an LCM echo (receive,
# republish, no model) in the same runs, over UDP multicast on loopback in a
# private network namespace (as the integration tests do): RUNS runs of
# SECONDS at 1 kHz with 1 and with 10 packages, then the medians over the
# runs of the monitor's and the echo's latency and of their ratio
# (docs/lcm-latency.md).  With "rates", then rising rates with 1 package
# until states are lost.
# usage: bench/lcm_latency.sh BUILD_DIR [rates]   (configured with -DSW_BUILD_BENCH=ON)
#        RUNS=5 SECONDS_PER_RUN=10 by default; SCENE=FILE instead of the test crate
set -eu
if [ -z "${SW_IN_NETNS:-}" ]; then
    export SW_IN_NETNS=1
    if unshare -rn true 2>/dev/null; then exec unshare -rn sh "$0" "$@"; fi
    exec unshare -n sh "$0" "$@"
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo
B=$(cd "$1" && pwd)
HERE=$(cd "$(dirname "$0")" && pwd)
SCENE=${SCENE:-"$HERE/../tests/lcm/crate.ini"}
RUNS=${RUNS:-5}
SECS=${SECONDS_PER_RUN:-10}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# A big receive buffer, as docs/lcm.md recommends above 1 kHz.
URL="udpm://239.255.76.67:7790?ttl=0&recv_buf_size=4194304"

run() { # RATE SECONDS PACKAGES
    scenes=""
    i=1
    while [ "$i" -le "$3" ]; do
        sed "s/^name .*/name = crate-$i/" "$SCENE" >"$T/s$i.ini"
        scenes="$scenes --scene $T/s$i.ini"
        i=$((i + 1))
    done
    # shellcheck disable=SC2086
    "$B/swaywatch" monitor -l "$URL" $scenes ${MONITOR_OPTS:-} 2>"$T/monitor.err" &
    mon=$!
    "$B/bench/lcm_latency" echo "$URL" "$3" &
    echo=$!
    sleep 0.5
    rc=0
    "$B/bench/lcm_latency" "$URL" "$1" "$2" "$3" "$mon" "$echo" || rc=$?
    kill -INT "$mon" "$echo"
    wait "$mon" || true
    wait "$echo" || true
    return $rc
}

# median of the numbers on stdin
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "# $(date -u +%Y-%m-%dT%H:%MZ), nproc $(nproc), $(lscpu | sed -n 's/^Model name: *//p')"
echo "# $RUNS runs of $SECS s at 1 kHz per package count"
for p in 1 10; do
    : >"$T/runs-$p"
    r=1
    while [ "$r" -le "$RUNS" ]; do
        run 1000 "$SECS" "$p" | tee -a "$T/runs-$p" || true
        r=$((r + 1))
    done
    f="$T/runs-$p"
    col() { sed -n "s/^$1.* latency median \([0-9]*\) us, p99 \([0-9]*\) us.*/\\$2/p" "$f" | median; }
    rat() { sed -n "s/^ratio monitor\/echo: median \([0-9.]*\), p99 \([0-9.]*\)/\\$1/p" "$f" | median; }
    lost=$(sed -n 's/^monitor: .*(lost \([0-9]*\)).*/\1/p' "$f" | awk '{s += $1} END {print s + 0}')
    elost=$(sed -n 's/^echo   : .*(lost \([0-9]*\)).*/\1/p' "$f" | awk '{s += $1} END {print s + 0}')
    echo "SUMMARY packages $p: medians over $RUNS runs: monitor median $(col monitor 1) us p99 $(col monitor 2) us;" \
        "echo median $(col echo 1) us p99 $(col echo 2) us; ratio median $(rat 1) p99 $(rat 2);" \
        "states lost: monitor $lost, echo $elost"
done
if [ "${2:-}" = rates ]; then
    for r in 2000 5000 10000 20000 30000 40000 50000; do
        run "$r" 5 1 || true
    done
fi
