#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Hostile lcm-logger files: length fields far beyond the file (0x7fffffff,
# negative, just under LCM's 256 MB limit) never crash replay or monitor
# --lcm-url file://, under a memory limit too; each bad header is one
# corrupted region, reported with its byte offset and reason, and the
# events after it are read.
# usage: lcmlog_hostile.sh SWAYWATCH SW_LCM_TOOL SCENE SANITIZED(0|1)
set -eu
SW=$1 TOOL=$2 SCENE=$3 SANITIZED=$4
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}

# 20 events of 81 bytes (28 header + "ACCEL" + 48 data).
"$TOOL" mklog "$T/clean.lcmlog" --rate 500 --duration 0.038

# craft NAME OFFSET-IN-HEADER VALUE: 10 good events, event 10 with the
# 32-bit field at OFFSET (20: channel length, 24: data length) set to
# VALUE, 9 good events.
craft() {
    python3 - "$T/clean.lcmlog" "$T/$1.lcmlog" "$2" "$3" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
ev = 81
assert len(data) == 20 * ev
struct.pack_into(">I", data, 10 * ev + int(sys.argv[3]), int(sys.argv[4], 0))
open(sys.argv[2], "wb").write(bytes(data))
PY
}
craft data7fff 24 0x7fffffff
craft chan7fff 20 0x7fffffff
craft dataneg 24 0x80000000
craft chanzero 20 0
craft data256m 24 0x0ffffff0 # under LCM's 256 MB limit, past the end of the file

for name in data7fff chan7fff dataneg chanzero data256m; do
    rc=0
    "$SW" replay "$T/$name.lcmlog" --scene "$SCENE" --settle 0 >/dev/null 2>"$T/err" || rc=$?
    [ "$rc" -eq 0 ] || fail "$name: replay exit $rc, expected 0"
    grep -q '19 events, 19 on the accel channel, 0 on other channels, 1 corrupted region' \
        "$T/err" || fail "$name: counts"
    grep -q "swaywatch: $T/$name.lcmlog: byte 810: corrupted region of 81 bytes skipped: " \
        "$T/err" || fail "$name: the region is not reported with its offset"
    rc=0
    "$SW" replay "$T/$name.lcmlog" --scene "$SCENE" --strict -q 2>"$T/err" || rc=$?
    [ "$rc" -eq 2 ] || fail "$name: --strict exit $rc, expected 2"
done
# reason NAME TEXT: replay says why the region was skipped
reason() {
    "$SW" replay "$T/$1.lcmlog" --scene "$SCENE" --settle 0 >/dev/null 2>"$T/err" || true
    grep -qF "$2" "$T/err" || fail "$1: reason"
}
reason data256m 'data length 268435440 runs past the end of the file (777 bytes left after the channel)'
reason data7fff 'data length 2147483647 is beyond the 268435456 bytes LCM allows'
reason dataneg 'data length -2147483648 is negative'
reason chan7fff 'channel length 2147483647 is not 1 to 63'
reason chanzero 'channel length 0 is not 1 to 63'
"$SW" replay "$T/data7fff.lcmlog" --scene "$SCENE" --settle 0 -q 2>"$T/err" || true
grep -q "swaywatch: $T/data7fff.lcmlog: 1 corrupted regions skipped" "$T/err" ||
    fail "--quiet: the region is not counted on stderr"

# Under a memory limit (not with the sanitizers, which reserve terabytes
# of address space).
if [ "$SANITIZED" = 0 ]; then
    for name in data7fff data256m; do
        rc=0
        (ulimit -v 120000 && exec "$SW" replay "$T/$name.lcmlog" --scene "$SCENE" --settle 0 -q) \
            2>"$T/err" || rc=$?
        [ "$rc" -eq 0 ] || fail "$name under ulimit -v: exit $rc"
    done
fi

# monitor --lcm-url file://: liblcm's file provider would read the
# damaged log itself; the log is checked first and refused.
for name in data7fff data256m chanzero; do
    rc=0
    timeout 20 "$SW" monitor --lcm-url "file://$T/$name.lcmlog?speed=0" --scene "$SCENE" \
        2>"$T/err" || rc=$?
    [ "$rc" -eq 2 ] || fail "monitor $name: exit $rc, expected 2"
    grep -q "swaywatch: monitor: $T/$name.lcmlog: 1 corrupted region (the first at byte 810: " \
        "$T/err" || fail "monitor $name: message"
done
# A clean log passes the check (what the monitor does at its end is not
# tested here).
rc=0
timeout --foreground -k 20 -s INT 5 "$SW" monitor --lcm-url "file://$T/clean.lcmlog?speed=0" --scene "$SCENE" \
    2>"$T/err" || rc=$?
[ "$rc" -lt 128 ] || fail "monitor on a clean file:// log: exit $rc"
! grep -q 'corrupted' "$T/err" || fail "monitor refused a clean file:// log"
echo "ok"
