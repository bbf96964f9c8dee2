# SPDX-License-Identifier: GPL-3.0-or-later
# lib.sh - helpers sourced by the command-line tests (POSIX sh).
# Every test is run by ctest as: sh TEST.sh SWAYWATCH SOURCE_DIR
set -eu
SW=$1
SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT INT TERM

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

# run CMD...: runs CMD with stdout in $TMP/out and stderr in $TMP/err; its
# exit status in $RC.
run() {
    set +e
    "$@" >"$TMP/out" 2>"$TMP/err"
    RC=$?
    set -e
}

show() {
    echo "--- stdout" >&2
    head -40 "$TMP/out" >&2
    echo "--- stderr" >&2
    head -40 "$TMP/err" >&2
}

# expect_rc N WHAT
expect_rc() {
    [ "$RC" -eq "$1" ] || {
        show
        fail "$2: exit status $RC, expected $1"
    }
}

# expect_err TEXT WHAT: stderr contains TEXT (fixed string)
expect_err() {
    grep -qF -- "$1" "$TMP/err" || {
        show
        fail "$2: stderr lacks '$1'"
    }
}

# Every line on stderr carries the prefix (continuation lines of a
# multi-line message start with blanks).
expect_prefixed_err() {
    [ -s "$TMP/err" ] || fail "$1: nothing on stderr"
    if grep -v -e '^swaywatch: ' -e '^ ' "$TMP/err" >/dev/null; then
        show
        fail "$1: stderr line without the 'swaywatch: ' prefix"
    fi
}

# json_check FILE PYTHON-EXPR: FILE is valid JSON and EXPR (over j) is true.
json_check() {
    python3 -m json.tool "$1" >/dev/null || fail "$1 is not valid JSON"
    python3 - "$1" "$2" <<'PY' || fail "$1: check failed: $2"
import json, sys
j = json.load(open(sys.argv[1]))
ok = eval(sys.argv[2])
if not ok:
    print(json.dumps(j, indent=1)[:3000], file=sys.stderr)
sys.exit(0 if ok else 1)
PY
}
