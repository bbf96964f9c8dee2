#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# lcm-logger logs that cannot seek (a pipe, a FIFO, standard input) are
# read whole, in one pass, with the bytes read to tell the log's kind: the
# same counts and summary as the file itself.
# usage: lcmlog_pipe.sh SWAYWATCH SW_LCM_TOOL SCENE
set -eu
SW=$1 TOOL=$2 SCENE=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}

# 20001 events, 1.6 MB: many times the first chunk read to tell the kind.
"$TOOL" mklog "$T/big.lcmlog" --rate 500 --duration 40
"$SW" replay "$T/big.lcmlog" --scene "$SCENE" --settle 0 --json >"$T/file.json" 2>"$T/err" ||
    fail "replay of the file"
grep -q ': 20001 events, 20001 on the accel channel' "$T/err" || fail "the file itself"

check() { # WHAT: the run's counts and summary are the file's
    grep -q ': 20001 events, 20001 on the accel channel, 0 on other channels, 0 corrupted' \
        "$T/err" || fail "$1: not every event read"
    grep -q 'accel samples: 20001 = accepted 20001' "$T/err" || fail "$1: samples"
    sed 's/"log": .*/"log": X,/' "$T/file.json" >"$T/a"
    sed 's/"log": .*/"log": X,/' "$T/pipe.json" >"$T/b"
    cmp -s "$T/a" "$T/b" || fail "$1: summary differs from the file's"
}

sh -c 'cat "$1" | "$2" replay /dev/stdin --scene "$3" --settle 0 --json' sh "$T/big.lcmlog" \
    "$SW" "$SCENE" >"$T/pipe.json" 2>"$T/err" || fail "cat | replay /dev/stdin: exit $?"
check "cat | replay /dev/stdin"

cat "$T/big.lcmlog" | "$SW" replay - --scene "$SCENE" --settle 0 --json >"$T/pipe.json" \
    2>"$T/err" || fail "cat | replay -: exit $?"
check "cat | replay -"

mkfifo "$T/fifo"
cat "$T/big.lcmlog" >"$T/fifo" &
"$SW" replay "$T/fifo" --scene "$SCENE" --settle 0 --json >"$T/pipe.json" 2>"$T/err" ||
    fail "replay FIFO: exit $?"
wait
check "replay FIFO"
echo "ok"
