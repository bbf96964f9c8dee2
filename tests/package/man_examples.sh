#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The EXAMPLES of the manual pages work: every swaywatch command line in an
# example block (.EX ... .EE) of docs/man/*.h2m and docs/man/swaywatch-scene.5
# is run, as printed, in a scratch folder with E set to a copy of the
# installed example files.  A command must exit 0 (0 or 1 with
# --fail-on-overturn) and write the files it names with --out, --events,
# --report, --wide or --plot.  The monitor and watch run until SIGINT: each is given 2 s in a
# private network namespace (only loopback, with LCM's multicast route), and
# is skipped, saying so, where no namespace can be made.  timeout signals
# the command alone (--foreground): without it, it signals its whole process
# group too, and a second SIGINT that reaches LeakSanitizer's tracer while
# the sanitized program checks for leaks at its exit can hang both.
# usage: man_examples.sh SWAYWATCH SOURCE_DIR
set -eu
SW=$1 SRC=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "man_examples.sh: $*" >&2; exit 1; }

# What the package installs in share/swaywatch/examples (scripts/package.cmake).
mkdir -p "$T/E" "$T/bin" "$T/run"
for f in crate.ini crate-on-frame.ini crate-on-cushion.ini braking-pothole.csv \
    hard-stop-overturn.csv; do
    cp "$SRC/sample_logs/$f" "$T/E/"
done
ln -s "$(cd "$(dirname "$SW")" && pwd)/$(basename "$SW")" "$T/bin/swaywatch"
export PATH="$T/bin:$PATH" E="$T/E"

netns=0
if unshare -n true 2>/dev/null; then netns=1; fi
monitor=1
if ! "$SW" monitor --help >/dev/null 2>&1; then monitor=0; fi
watch=1
if ! "$SW" watch --help >/dev/null 2>&1; then watch=0; fi

# One command per line: roff escapes undone, continuation lines joined,
# "E=..." lines left out (E is set above).
for page in "$SRC"/docs/man/*.h2m "$SRC/docs/man/swaywatch-scene.5"; do
    awk -v page="$(basename "$page")" '
        /^\.EX/ { on = 1; next }
        /^\.EE/ { on = 0; next }
        !on { next }
        {
            gsub(/\\-/, "-"); gsub(/\\e/, "\\")
            if (cmd != "") { cmd = cmd " " $0 } else if ($1 == "swaywatch") { cmd = $0 } else next
            if (cmd ~ /\\$/) { sub(/ *\\$/, "", cmd); next }
            gsub(/  +/, " ", cmd)
            print page "\t" cmd; cmd = ""
        }' "$page"
done >"$T/commands"
[ "$(wc -l <"$T/commands")" -ge 12 ] || fail "only $(wc -l <"$T/commands") example commands found"

n=0 skipped=0
while IFS='	' read -r page cmd; do
    case "$cmd" in
    "swaywatch monitor "* | "swaywatch watch "*)
        have=$monitor
        case "$cmd" in "swaywatch watch "*) have=$watch ;; esac
        if [ "$have" = 0 ] || [ "$netns" = 0 ]; then
            why="no network namespace"
            [ "$have" = 1 ] || why="a build without LCM or curses: no such command"
            echo "man_examples.sh: $page: skipped ($why): $cmd"
            skipped=$((skipped + 1))
            continue
        fi
        rc=0
        (cd "$T/run" && unshare -n sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo &&
            exec timeout --foreground --preserve-status -k 20 -s INT 2 sh -c "exec $1"' sh "$cmd") \
            >"$T/out" 2>&1 </dev/null || rc=$?
        [ "$rc" -eq 0 ] || { cat "$T/out" >&2; fail "$page: exit $rc: $cmd"; }
        case "$cmd" in "swaywatch monitor "*)
            grep -q 'monitor stopped (SIGINT)' "$T/out" ||
                { cat "$T/out" >&2; fail "$page: the monitor did not run until SIGINT: $cmd"; } ;;
        esac
        ;;
    *)
        rc=0
        (cd "$T/run" && sh -c "$cmd") >"$T/out" 2>&1 </dev/null || rc=$?
        case "$rc:$cmd" in
        0:* | 1:*--fail-on-overturn*) ;;
        *) cat "$T/out" >&2; fail "$page: exit $rc: $cmd" ;;
        esac
        for f in $(printf '%s\n' "$cmd" | awk '{for (i = 1; i < NF; i++)
                if ($i ~ /^--(out|events|plot|wide|report)$/) print $(i + 1)}'); do
            [ -s "$T/run/$f" ] || fail "$page: $f not written: $cmd"
        done
        ;;
    esac
    n=$((n + 1))
    echo "man_examples.sh: $page: ok: $cmd"
done <"$T/commands"
echo "man_examples.sh: ok ($n commands run, $skipped skipped)"
