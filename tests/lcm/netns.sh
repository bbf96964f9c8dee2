# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the UDP multicast tests of this folder (sh): a network
# namespace of their own (../netns_enter.sh; no skip: CI runs these as
# root, where both forms of unshare work), a work folder, and helpers.
. "$(dirname "$0")/../netns_enter.sh"

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

# wait_subscribed N: LCM has no handshake.  lcm_create() joins the
# multicast group with the send socket, lcm_subscribe() with the receive
# socket and then runs a self-test during which every other message is
# dropped.  Wait until the group 239.255.76.67 (434CFFEF in /proc/net/igmp)
# has N members - two per subscribed process - then leave the self-tests a
# moment.  A fixed sleep lost messages when the machine was busy.
wait_subscribed() {
    n=0
    until [ "$(awk '$1 == "434CFFEF" { print $2 }' /proc/net/igmp)" -ge "$1" ] 2>/dev/null; do
        n=$((n + 1))
        [ "$n" -le 300 ] || fail "fewer than $1 members in the LCM group after 30 s"
        sleep 0.1
    done
    sleep 0.3
}

# wait_for FILE TEXT: until FILE holds TEXT (e.g. a status line's counts).
wait_for() {
    n=0
    until grep -qF -- "$2" "$1"; do
        n=$((n + 1))
        [ "$n" -le 300 ] || fail "no '$2' in $1 after 30 s"
        sleep 0.1
    done
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

# replay_published LOG: `swaywatch replay` of LOG ($SW, $SCENE), publishing
# to a log; its dump in $T/replay.txt, its summary in $T/replay.json.
replay_published() {
    "$SW" replay "$1" --scene "$SCENE" --settle 0 --speed 0 --max-rejected 100 \
        --publish "file://$T/replay.lcmlog?mode=w" --json >"$T/replay.json"
    "$TOOL" dump "$T/replay.lcmlog" >"$T/replay.txt"
}

# same_physics PATTERN WHAT: the live dump ($T/live.txt) has an alarm line
# matching PATTERN (else fail WHAT), publishes the same states and alarms
# as the replay, and its peak theta agrees with the replay's summary to
# 1e-4 rad; sets $peak.
same_physics() {
    physics "$T/live.txt" >"$T/live.phys"
    physics "$T/replay.txt" >"$T/replay.phys"
    grep -q "$1" "$T/live.phys" || fail "$2"
    diff "$T/live.phys" "$T/replay.phys" || fail "live and replayed states or alarms differ"
    peak=$(sed -n 's/^state crate-A count [0-9]* max_abs_theta \([^ ]*\) .*/\1/p' "$T/live.txt")
    close "$(json_theta "$T/replay.json")" "$peak" 1e-4 || fail "peak theta"
}
