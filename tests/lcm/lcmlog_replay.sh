#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# `swaywatch replay` of lcm-logger files (read in-process, no network):
# corrupted regions are skipped and counted, each losing only its own
# event; --strict stops at the first; other channels are counted; a log
# without the accel channel is an error (2).
# usage: lcmlog_replay.sh SWAYWATCH SW_LCM_TOOL SCENE
set -eu
SW=$1 TOOL=$2 SCENE=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    exit 1
}

"$TOOL" mklog "$T/clean.lcmlog" --rate 500 --duration 3
"$SW" replay "$T/clean.lcmlog" --scene "$SCENE" --settle 0 --json >"$T/clean.json" 2>"$T/clean.err"
grep -q '1501 events, 1501 on the accel channel, 0 on other channels, 0 corrupted' "$T/clean.err" ||
    fail "clean log"

# Events are 81 bytes (28 header + "ACCEL" + 48 data).  Damage four of them:
# a data length past the end of the file (event 100), junk between events
# 200 and 201 (the reader drops 200: the bytes after it are no sync word),
# a bad channel length (event 300), a truncated last event.
python3 - "$T/clean.lcmlog" "$T/bad.lcmlog" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
ev = 81
assert len(data) == 1501 * ev
struct.pack_into(">i", data, 100 * ev + 24, 0x7FFF0000)  # datalen of event 100
struct.pack_into(">i", data, 300 * ev + 20, 5000)        # channellen of event 300
data[201 * ev:201 * ev] = b"\x13" * 13                   # junk before event 201
open(sys.argv[2], "wb").write(bytes(data[:-10]))         # last event cut short
PY
"$SW" replay "$T/bad.lcmlog" --scene "$SCENE" --settle 0 --json >"$T/bad.json" 2>"$T/bad.err" ||
    fail "replay of the damaged log: exit $?"
cat "$T/bad.err"
grep -q '1497 events, 1497 on the accel channel, 0 on other channels, 4 corrupted regions' \
    "$T/bad.err" || fail "corrupted regions not counted as expected"
grep -q 'accel samples: 1497 = accepted 1497 + rejected 0; lost 3 (by seq)' "$T/bad.err" ||
    fail "samples of the damaged log"

rc=0
"$SW" replay "$T/bad.lcmlog" --scene "$SCENE" --strict -q 2>"$T/strict.err" || rc=$?
[ "$rc" -eq 2 ] || fail "--strict on a damaged log: exit $rc, expected 2"
grep -q 'strict' "$T/strict.err" || fail "--strict message"

# Accel on another channel: counted, and --accel-channel (or its old name
# --channel) finds it (anchored regex).
"$TOOL" mklog "$T/other.lcmlog" --rate 100 --duration 1 --channel IMU_ACCEL
rc=0
"$SW" replay "$T/other.lcmlog" --scene "$SCENE" -q 2>"$T/other.err" || rc=$?
[ "$rc" -eq 2 ] || fail "no accel channel: exit $rc, expected 2"
grep -q '101 events, 0 on the accel channel, 101 on other channels' "$T/other.err" ||
    fail "other channels not counted"
"$SW" replay "$T/other.lcmlog" --scene "$SCENE" --channel 'IMU_.*' >/dev/null 2>"$T/re.err" ||
    fail "--channel IMU_.*"
grep -q '101 on the accel channel' "$T/re.err" || fail "--channel regex"
"$SW" replay "$T/other.lcmlog" --scene "$SCENE" --accel-channel 'IMU_.*' >/dev/null 2>"$T/re2.err" ||
    fail "--accel-channel IMU_.*"
grep -q '101 on the accel channel' "$T/re2.err" || fail "--accel-channel regex"
rc=0
"$SW" replay "$T/other.lcmlog" --scene "$SCENE" --channel 'ACCEL' -q 2>/dev/null || rc=$?
[ "$rc" -eq 2 ] || fail "--channel is anchored: ACCEL must not match IMU_ACCEL"

# Options of lcm-logger files are refused for CSV logs, and vice versa.
printf '0,0\n0.001,0\n' >"$T/x.csv"
rc=0
"$SW" replay "$T/x.csv" --scene "$SCENE" --publish '' -q 2>"$T/csv.err" || rc=$?
[ "$rc" -eq 2 ] && grep -q "is for lcm-logger files" "$T/csv.err" || fail "--publish on CSV"
rc=0
"$SW" replay "$T/clean.lcmlog" --scene "$SCENE" --time-col 1 -q 2>"$T/lcm.err" || rc=$?
[ "$rc" -eq 2 ] && grep -q "is for CSV logs" "$T/lcm.err" || fail "--time-col on an lcm log"
echo "ok"
