#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The licence identifier at the top of every source file (LICENSE: the
# project is GPL-3.0-or-later, as GSL, which it links, requires).
#
#   scripts/spdx.sh          add the line where it is missing
#   scripts/spdx.sh --check  list the files without it; exit 1 if any
#
# Source files: C and headers, LCM types, Java, shell, Python, CMake,
# gnuplot and the packaging scripts.  Data (CSV, INI, logs), documents and
# generated files carry none.  The line goes first, or second after a
# "#!" line, in the file's own comment syntax.
set -eu
cd "$(dirname "$0")/.."
ID="SPDX-License-Identifier: GPL-3.0-or-later"
check=0
[ "${1:-}" = "--check" ] && check=1

comment_for() {
    case "$1" in
    *.c | *.h | *.h.in | *.lcm | *.java) echo "/* $ID */" ;;
    *.sh | *.py | *.cmake | */CMakeLists.txt | CMakeLists.txt | *.gp | *.slurm | \
        .ci/run | scripts/bash-completion/* | scripts/debian/postinst | scripts/debian/postrm | \
        scripts/debian/prerm) echo "# $ID" ;;
    *) echo "" ;;
    esac
}

missing=0
for f in $(git ls-files); do
    case "$f" in tests/fuzz/corpus/* | tests/fuzz/regressions/* | sample_logs/* | tests/data/*) continue ;; esac
    line=$(comment_for "$f")
    [ -n "$line" ] || continue
    head -3 "$f" | grep -q "SPDX-License-Identifier" && continue
    missing=$((missing + 1))
    if [ "$check" -eq 1 ]; then
        echo "$f"
        continue
    fi
    tmp=$(mktemp)
    if head -1 "$f" | grep -q '^#!'; then
        { head -1 "$f"; echo "$line"; tail -n +2 "$f"; } >"$tmp"
    else
        { echo "$line"; cat "$f"; } >"$tmp"
    fi
    cat "$tmp" >"$f" # keeps the file's mode
    rm -f "$tmp"
done
if [ "$check" -eq 1 ] && [ "$missing" -gt 0 ]; then
    echo "swaywatch spdx: $missing files without an SPDX line (scripts/spdx.sh adds it)" >&2
    exit 1
fi
exit 0
