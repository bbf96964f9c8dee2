#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Make the manual pages of swaywatch from its own --help and --version, with
# help2man: swaywatch.1 and one page per command (swaywatch-replay.1, ...).
# The commands are read from 'swaywatch --help', so a new command gets its
# page without touching this script.
#
# usage: mkman.sh SWAYWATCH OUTDIR
#
# help2man wants one program that answers --help and --version, and names the
# page after what --version prints; so each command is run through a small
# wrapper named swaywatch-CMD that prints "swaywatch-CMD (swaywatch) VERSION"
# and the copyright and licence lines of 'swaywatch --version', and
# capitalises "usage:" (help2man turns "Usage:" into the SYNOPSIS), joining
# the usage line's indented continuation lines to it.
#
# A command's page also gets the sections of swaywatch-CMD.h2m beside this
# script (its EXAMPLES), when there is one; every page's SEE ALSO names
# swaywatch-scene(5), the scene file format.
set -eu
SW=$1
OUT=$2
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"
rm -f "$OUT"/swaywatch*.1

version=$("$SW" --version | sed -n '1s/^swaywatch //p')
[ -n "$version" ] || { echo "mkman.sh: '$SW --version' printed no version" >&2; exit 1; }
# The copyright and licence lines after it: help2man makes them the COPYRIGHT section.
LICENCE=$("$SW" --version | sed 1d)
export LICENCE
# "  replay     replay a recorded log ..." lines of the Commands: paragraph.
"$SW" --help | awk '/^Commands:/ {on = 1; next} on && /^$/ {exit}
                    on && /^  [a-z]/ {name = $1; sub(/^  [a-z-]+ +/, ""); print name "\t" $0}' \
    >"$TMP/commands"
[ -s "$TMP/commands" ] || { echo "mkman.sh: no commands in '$SW --help'" >&2; exit 1; }

USAGE='1{s/^usage:/Usage:/
:a
N
s/\n  *\([^ ]\)/ \1/
ta
}'
export USAGE

page() { # NAME SUMMARY PROGRAM SEEALSO
    printf '[SEE ALSO]\n%s,\n.BR swaywatch\\-scene (5)\n' "$4" >"$TMP/include"
    "${HELP2MAN:-help2man}" --no-info --section=1 --name="$2" --source="swaywatch $version" \
        --manual="swaywatch manual" --include="$TMP/include" --opt-include="$HERE/$1.h2m" \
        --output="$OUT/$1.1" "$3"
}

all_cmds=""
while IFS='	' read -r cmd summary; do
    all_cmds="$all_cmds$cmd "
    w="$TMP/swaywatch-$cmd"
    cat >"$w" <<WRAP
#!/bin/sh
case "\$1" in
--version) echo "swaywatch-$cmd (swaywatch) $version"; printf '%s\n' "\$LICENCE" ;;
*) "$SW" $cmd --help | sed "\$USAGE" ;;
esac
WRAP
    chmod +x "$w"
    page "swaywatch-$cmd" "$summary" "$w" ".BR swaywatch (1)"
done <"$TMP/commands"

see=""
for c in $all_cmds; do see="$see${see:+,
}.BR swaywatch-$c (1)"; done
cat >"$TMP/swaywatch" <<WRAP
#!/bin/sh
case "\$1" in
--version) echo "swaywatch $version"; printf '%s\n' "\$LICENCE" ;;
*) "$SW" --help | sed "\$USAGE" ;;
esac
WRAP
chmod +x "$TMP/swaywatch"
page swaywatch "tip-over watch for floating cargo on a truck" "$TMP/swaywatch" "$see"
