#!/bin/sh
# Runs lcm_latency against `swaywatch monitor` over UDP multicast on
# loopback, in a private network namespace (as the integration tests do):
# 1 kHz with 1 and 10 packages (with the monitor's CPU use), then rising
# rates with 1 package until states are lost.
# usage: bench/lcm_latency.sh BUILD_DIR   (configured with -DSW_BUILD_BENCH=ON)
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
SCENE="$HERE/../tests/lcm/crate.ini"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# A big receive buffer, as docs/lcm.md recommends above 1 kHz.
URL="udpm://239.255.76.67:7790?ttl=0&recv_buf_size=4194304"

run() { # RATE SECONDS PACKAGES
    set --  "$1" "$2" "$3"
    scenes=""
    i=1
    while [ "$i" -le "$3" ]; do
        sed "s/^name .*/name = crate-$i/" "$SCENE" >"$T/s$i.ini"
        scenes="$scenes --scene $T/s$i.ini"
        i=$((i + 1))
    done
    # shellcheck disable=SC2086
    "$B/swaywatch" monitor -l "$URL" $scenes 2>"$T/monitor.err" &
    mon=$!
    sleep 0.5
    rc=0
    "$B/bench/lcm_latency" "$URL" "$1" "$2" "$3" "$mon" || rc=$?
    kill -INT "$mon"
    wait "$mon" || true
    return $rc
}

echo "# $(date -u +%Y-%m-%d), $(nproc) CPUs: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
run 1000 10 1 || true
run 1000 10 10 || true
for r in 2000 5000 10000 20000 30000 40000 50000; do
    run "$r" 5 1 || true
done
