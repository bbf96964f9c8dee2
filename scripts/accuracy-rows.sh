#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The "Accuracy option rows" of docs/accuracy-speed.md, from the code: the
# rows[] table of src/lib/core/accuracy.c, one block per model, written between
# the document's accuracy-rows markers, so that the document shows the
# rows the program uses and cannot disagree with them.  (The benchmark
# prints the rows its own run would choose, under another title.)
#
#   scripts/accuracy-rows.sh          rewrite the blocks in place
#   scripts/accuracy-rows.sh --check  change nothing; exit 1 if they differ
set -eu
cd "$(dirname "$0")/.."
SRC=src/lib/core/accuracy.c
DOC=docs/accuracy-speed.md
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The entries of rows[], one per line: {SW_MODEL_X, tol, "scheme", dt}
awk '/^static const acc_row_t rows\[\] = \{/ {on = 1; next}
     on && /^\};/ {on = 0}
     on' "$SRC" | tr -d '\n' | grep -o '{SW_MODEL_[A-Z]*, *[^}]*}' >"$TMP/rows"
[ -s "$TMP/rows" ] || { echo "accuracy-rows: no rows[] in $SRC" >&2; exit 1; }
{
    for m in $(sed 's/^{SW_MODEL_\([A-Z]*\),.*/\1/' "$TMP/rows" | awk '!seen[$0]++'); do
        name=$(echo "$m" | tr 'A-Z' 'a-z')
        echo "Accuracy option rows for \`$name\` (in use: src/lib/core/accuracy.c, written here by"
        echo "scripts/accuracy-rows.sh; a row serves the tolerances from the one before it down"
        echo "to its own, tol in rad, dt in s, 0 the scheme's default):"
        echo
        echo '```'
        grep "^{SW_MODEL_$m," "$TMP/rows" | sed 's/^/    /; s/$/,/'
        echo '```'
        echo
    done
} >"$TMP/block"
awk -v blk="$TMP/block" '
    /<!-- accuracy-rows:begin -->/ {print; while ((getline l < blk) > 0) print l; skip = 1; found++; next}
    /<!-- accuracy-rows:end -->/ {skip = 0}
    !skip {print}
    END {if (found != 1) exit 3}' "$DOC" >"$TMP/doc" || {
    echo "accuracy-rows: $DOC needs one <!-- accuracy-rows:begin --> ... end --> pair" >&2
    exit 1
}
if [ "${1:-}" = "--check" ]; then
    if ! cmp -s "$TMP/doc" "$DOC"; then
        diff "$DOC" "$TMP/doc" >&2 || true
        echo "accuracy-rows: $DOC disagrees with $SRC (scripts/accuracy-rows.sh fixes it)" >&2
        exit 1
    fi
    exit 0
fi
cp "$TMP/doc" "$DOC"
