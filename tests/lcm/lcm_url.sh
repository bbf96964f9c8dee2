#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# LCM URLs are read as liblcm 1.3.1 reads them (lcm_parse_url in lcm.c,
# the file provider's options in lcm_file.c): options after every '?',
# split on '&', the last of a key wins, a mode other than r, w or a reads.
# Whatever the spelling, a file:// URL that makes LCM read a damaged log
# is refused before liblcm's reader (which trusts the length fields and
# crashes on them) gets it, in monitor and watch; and a URL that makes
# LCM write a file is never one of the command's inputs.
# usage: lcm_url.sh SWAYWATCH SW_LCM_TOOL SCENE
set -eu
SW=$1 TOOL=$2 SCENE=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}

# 20 events of 81 bytes; the 11th with a data length of 0x7fffffff.
"$TOOL" mklog "$T/clean.lcmlog" --rate 500 --duration 0.038
python3 - "$T/clean.lcmlog" "$T/bad.lcmlog" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
struct.pack_into(">I", data, 10 * 81 + 24, 0x7FFFFFFF)
open(sys.argv[2], "wb").write(bytes(data))
PY
cp "$T/bad.lcmlog" "$T/bad.orig"

# Spellings that liblcm reads as mode r (the old check read the first
# mode=, or only the options after the first '?', and let them through).
for opts in 'mode=w&mode=r' 'mode=a&speed=0&mode=r' 'mode=wx' 'mode=' 'mode' 'mode=W' \
    'speed=0?mode=r' 'mode=w?mode=r' 'mode=w&mode=r=x'; do
    url="file://$T/bad.lcmlog?$opts"
    rc=0
    timeout 20 "$SW" monitor --lcm-url "$url" --scene "$SCENE" >/dev/null 2>"$T/err" || rc=$?
    [ "$rc" -eq 2 ] || fail "monitor --lcm-url '$url': exit $rc, expected 2 (refused)"
    grep -q "swaywatch: monitor: $T/bad.lcmlog: 1 corrupted region" "$T/err" ||
        fail "monitor --lcm-url '$url': not refused as damaged"
    cmp -s "$T/bad.lcmlog" "$T/bad.orig" || fail "monitor --lcm-url '$url': the log was changed"
    if "$SW" --help | grep -q '^  watch'; then
        rc=0
        timeout 20 "$SW" watch --once --wait 0.1 -l "$url" >/dev/null 2>"$T/err" || rc=$?
        [ "$rc" -eq 2 ] || fail "watch -l '$url': exit $rc, expected 2 (refused)"
        grep -q "swaywatch: watch: $T/bad.lcmlog: 1 corrupted region" "$T/err" ||
            fail "watch -l '$url': not refused as damaged"
    fi
done
# The same through $LCM_DEFAULT_URL.
rc=0
LCM_DEFAULT_URL="file://$T/bad.lcmlog?mode=w&mode=r" timeout 20 "$SW" monitor \
    --scene "$SCENE" >/dev/null 2>"$T/err" || rc=$?
[ "$rc" -eq 2 ] || fail "LCM_DEFAULT_URL: exit $rc, expected 2"

# Spellings that liblcm reads as a write: an output, never an input.
cp "$T/clean.lcmlog" "$T/in.lcmlog"
for opts in 'speed=0?mode=w' 'mode=r&mode=w' 'x?mode=a'; do
    rc=0
    "$SW" replay "$T/in.lcmlog" --scene "$SCENE" -q \
        --publish "file://$T/in.lcmlog?$opts" >/dev/null 2>"$T/err" || rc=$?
    [ "$rc" -eq 2 ] || fail "replay --publish file://LOG?$opts: exit $rc, expected 2"
    grep -q "that is the log being read" "$T/err" || fail "replay --publish ?$opts: message"
    cmp -s "$T/in.lcmlog" "$T/clean.lcmlog" || fail "replay --publish ?$opts: the log was changed"
    cp "$SCENE" "$T/s.ini"
    rc=0
    timeout 20 "$SW" monitor --scene "$T/s.ini" --lcm-url "file://$T/s.ini?$opts" \
        >/dev/null 2>"$T/err" || rc=$?
    [ "$rc" -eq 2 ] || fail "monitor --lcm-url file://SCENE?$opts: exit $rc, expected 2"
    grep -q "that is a scene file being read" "$T/err" || fail "monitor ?$opts: message"
    cmp -s "$T/s.ini" "$SCENE" || fail "monitor --lcm-url ?$opts: the scene was changed"
done

# --publish to a URL that LCM reads publishes nothing (and would read a
# damaged log): refused, naming the fix.
rc=0
"$SW" replay "$T/clean.lcmlog" --scene "$SCENE" -q \
    --publish "file://$T/bad.lcmlog?mode=w&mode=r" >/dev/null 2>"$T/err" || rc=$?
[ "$rc" -eq 2 ] || fail "replay --publish (read mode): exit $rc, expected 2"
grep -q "LCM reads that file instead of writing it" "$T/err" || fail "--publish read: message"
# and one that writes works: the log gets the states.
rc=0
"$SW" replay "$T/clean.lcmlog" --scene "$SCENE" -q \
    --publish "file://$T/out.lcmlog?speed=0?mode=w" >/dev/null 2>"$T/err" || rc=$?
[ "$rc" -eq 0 ] || fail "replay --publish ...?mode=w: exit $rc"
[ -s "$T/out.lcmlog" ] || fail "replay --publish ...?speed=0?mode=w wrote nothing"
echo "ok"
