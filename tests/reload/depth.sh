#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A reload may not give a package a lateral plane, or take it away: the
# monitor's input and engines were made with or without one.  A depth
# added to a scene on SIGHUP is refused with the reason, and the monitor
# goes on with the scenes it had, never judging the new depth along the
# truck only; so is a depth removed.  With --lat-axis none (one plane
# asked for) the same edit is applied.  memq://: no network.
# usage: depth.sh SWAYWATCH
set -eu
SW=$1
T=$(mktemp -d)
PID=""
trap '[ -n "$PID" ] && kill "$PID" 2>/dev/null; rm -rf "$T"' EXIT
fail() {
    echo "depth.sh: FAIL: $*" >&2
    cat "$T/err" >&2
    exit 1
}
crate() { # FILE [DEPTH LINE]
    printf '[package]\nname = crate-B\nheight = 2.0\nwidth = 0.728\nmass = 1000\n%s\n' "${2:-}" >"$1"
}
# reload OPTIONS DEPTH_BEFORE DEPTH_AFTER: the monitor's stderr in $T/err
reload() {
    crate "$T/b.ini" "$2"
    "$SW" monitor -l memq:// --scene "$T/b.ini" $1 2>"$T/err" &
    PID=$!
    sleep 0.5
    crate "$T/b.ini" "$3"
    kill -HUP "$PID"
    n=0
    until grep -q 'reload: .*\(applied\|rebuilt\)' "$T/err"; do
        n=$((n + 1))
        [ "$n" -le 100 ] || fail "no reload after 10 s"
        sleep 0.1
    done
    kill -INT "$PID"
    wait "$PID" || fail "monitor exited with $?"
    PID=""
}
reload "" "" "depth = 0.6"
grep -q 'crate-B: package.depth added: a package cannot gain or lose its lateral plane' "$T/err" ||
    fail "a depth added on reload was not refused"
grep -q 'not applied' "$T/err" || fail "the reload was applied"
reload "" "depth = 0.6" ""
grep -q 'package.depth removed' "$T/err" || fail "a depth removed on reload was not refused"
reload "--lat-axis none" "" "depth = 0.6"
grep -q 'crate-B rebuilt' "$T/err" || fail "--lat-axis none: the edit was not applied"
echo "ok"
