# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced (sh) by the tests that talk UDP multicast: re-runs the calling
# script in a new network namespace that has only loopback, and gives it
# the multicast route LCM's udpm provider needs (a fresh namespace has
# none, and lcm_create() then fails).  Nothing leaves the namespace:
# parallel tests and other LCM users on the host never see each other's
# traffic.  Without a namespace (neither root nor user namespaces) the test
# fails, or with NETNS_SKIP=1 set by the caller is skipped (exit 77).
if [ -z "${SW_IN_NETNS:-}" ]; then
    export SW_IN_NETNS=1
    for u in "unshare -rn" "unshare -n"; do
        if $u true 2>/dev/null; then exec $u sh "$0" "$@"; fi
    done
    if [ "${NETNS_SKIP:-0}" = 1 ]; then
        echo "$0: cannot make a network namespace: skipped"
        exit 77
    fi
    echo "$0: cannot create a network namespace (needs root or user namespaces)" >&2
    exit 1
fi
ip link set lo up
ip route add 224.0.0.0/4 dev lo
