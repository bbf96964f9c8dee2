# SPDX-License-Identifier: GPL-3.0-or-later
# lcmtest.sh - helpers of the tests that run the live monitor over LCM UDP
# multicast (soak.sh, memcheck-lcm.sh).  Sourced; FEED (sw_accel_feed) and
# URL must be set before the functions are called.

# enter_netns "$@": re-runs the calling script in a network namespace of
# its own - loopback only, with a multicast route on it - where no other
# process (or parallel test) shares the multicast group.  Exit 77 (skipped)
# if no namespace can be made.
enter_netns() {
    if [ -z "${SW_LCMTEST_NETNS:-}" ]; then
        if ! unshare -rn true 2>/dev/null; then
            echo "cannot create a network namespace (unshare -rn): skipped"
            exit 77
        fi
        exec unshare -rn env SW_LCMTEST_NETNS=1 sh "$0" "$@"
    fi
    ip link set lo up
    ip route add 224.0.0.0/4 dev lo
}

rss_kb() {
    awk '/^VmRSS:/ { print $2 }' "/proc/$1/status"
}

# The counts of the monitor's last status line (--status 1) in FILE.
last_status() {
    grep 'accepted' "$1" | tail -1 | sed 's/.*busy [^;]*; //'
}

# wait_idle FILE: until the monitor's status lines show the same counts
# three times running: it has handled everything queued.
wait_idle() {
    prev=""
    same=0
    n=0
    while [ "$same" -lt 3 ]; do
        sleep 1
        cur=$(last_status "$1")
        if [ -n "$cur" ] && [ "$cur" = "$prev" ]; then same=$((same + 1)); else same=0; fi
        prev=$cur
        n=$((n + 1))
        if [ "$n" -gt 300 ]; then
            echo "FAIL: the monitor never went idle" >&2
            return 1
        fi
    done
}

# wait_subscribed FILE: until the monitor (status lines in FILE) handles
# what is published.  Joining the group is not enough: LCM's subscriber
# then runs a self-test and drops every other message until it is done.
# So probes - empty messages, which the monitor refuses as "decode" - go
# out until one is counted; PROBES is then how many it counted.
wait_subscribed() {
    n=0
    while ! last_status "$1" | grep -q '(decode [0-9]'; do
        "$FEED" publish "$URL" --count 0 --empty 1 >/dev/null
        sleep 0.2
        n=$((n + 1))
        if [ "$n" -gt 600 ]; then
            echo "FAIL: the monitor did not subscribe within 2 minutes" >&2
            return 1
        fi
    done
    wait_idle "$1"
    PROBES=$(last_status "$1" | sed -n 's/.*(decode \([0-9]*\).*/\1/p')
}
