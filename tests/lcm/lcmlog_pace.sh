#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# replay --publish paces on the samples it accepts: a refused sample (NaN)
# stamped 20 s ahead of its neighbours must not stall the replay 20 s.
# usage: lcmlog_pace.sh SWAYWATCH SW_LCM_TOOL SCENE
set -eu
SW=$1 TOOL=$2 SCENE=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}

# 0.5 s at 1 kHz; sample 250 gets ax = NaN and a utime 20 s ahead.
"$TOOL" mklog "$T/ok.lcmlog" --rate 1000 --duration 0.5
python3 - "$T/ok.lcmlog" "$T/nan.lcmlog" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
ev = 81
k = 250
utime = struct.unpack_from(">q", data, k * ev + 33 + 8)[0]
struct.pack_into(">q", data, k * ev + 33 + 8, utime + 20000000)
struct.pack_into(">d", data, k * ev + 33 + 24, float("nan"))
open(sys.argv[2], "wb").write(bytes(data))
PY
# About 0.5 s of pacing; the stall would add 20.
rc=0
timeout 8 "$SW" replay "$T/nan.lcmlog" --scene "$SCENE" --settle 0 --speed 1 \
    --publish "file://$T/out.lcmlog?mode=w" >/dev/null 2>"$T/err" || rc=$?
[ "$rc" -eq 0 ] || fail "replay --publish --speed 1: exit $rc (124: stalled on a refused sample)"
grep -q 'accel samples: 501 = accepted 500 + rejected 1 (nonfinite 1)' "$T/err" ||
    fail "the NaN sample is not refused"
echo "ok"
