#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The C sources in the style of .clang-format (LCM's: Google base, 4-space
# indent, 100 columns), with Debian 12's clang-format (14).
#
#   scripts/format.sh          reformat every tracked .c and .h in place
#   scripts/format.sh --check  change nothing; list what is off, exit 1 if any
#
# The one commit that formatted the whole tree is in .git-blame-ignore-revs
# (git config blame.ignoreRevsFile .git-blame-ignore-revs).
set -eu
cd "$(dirname "$0")/.."
CF=${CLANG_FORMAT:-clang-format}
if ! command -v "$CF" >/dev/null 2>&1; then
    echo "swaywatch format: $CF not found (scripts/setup-debian.sh installs clang-format)" >&2
    exit 1
fi
files=$(git ls-files '*.c' '*.h' | grep -v '^tests/fuzz/corpus/')
if [ "${1:-}" = "--check" ]; then
    log=$(mktemp)
    trap 'rm -f "$log"' EXIT
    # shellcheck disable=SC2086
    if ! "$CF" --dry-run -Werror $files 2>"$log"; then
        grep -o '^[^:]*:[0-9]*:[0-9]*: error' "$log" | cut -d: -f1 | sort -u >&2
        echo "swaywatch format: the files above differ from .clang-format" \
            "(scripts/format.sh fixes them)" >&2
        exit 1
    fi
    exit 0
fi
# shellcheck disable=SC2086
"$CF" -i $files
