# Sourced by the UDP multicast tests (sh).  Re-runs the calling script in a
# new network namespace that has only loopback, and gives it the multicast
# route LCM's udpm provider needs (a fresh namespace has none, and
# lcm_create() then fails).  Nothing leaves the namespace: parallel tests
# and other LCM users on the host never see each other's traffic.  No skip:
# CI runs these as root, where both forms of unshare work.
if [ -z "${SW_IN_NETNS:-}" ]; then
    export SW_IN_NETNS=1
    if unshare -rn true 2>/dev/null; then exec unshare -rn sh "$0" "$@"; fi
    if unshare -n true 2>/dev/null; then exec unshare -n sh "$0" "$@"; fi
    echo "$0: cannot create a network namespace (needs root or user namespaces)" >&2
    exit 1
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo

T=$(mktemp -d)
PIDS=""
cleanup() {
    for p in $PIDS; do kill "$p" 2>/dev/null || true; done
    rm -rf "$T"
}
trap cleanup EXIT

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

# Physics lines of a dump (states, and alarms other than the input-level
# SENSOR_GAP (9) and INPUT_REJECTED (10), whose timing depends on arrival).
physics() {
    grep -E '^(state |alarm [0-9-]+ [^ ]+ ([1-8]) )' "$1" || true
}

# max_abs_theta of the first package in a JSON summary.
json_theta() {
    python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["packages"][0]["max_abs_theta"])' "$1"
}

# |a - b| <= tol
close() {
    python3 -c 'import sys; a,b,t=map(float,sys.argv[1:]); sys.exit(abs(a-b) > t)' "$1" "$2" "$3"
}
