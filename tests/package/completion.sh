#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The bash completion completes what the command offers: its commands, each
# command's options (read from its --help), values of the options that have
# a fixed set, and scene files for --scene.
# usage: completion.sh COMPLETION_FILE SWAYWATCH
set -eu
COMPLETION=$1
SW=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/bin" "$T/work/scenes"
ln -s "$SW" "$T/bin/swaywatch"
export PATH="$T/bin:$PATH"
fail() { echo "completion.sh: $*" >&2; exit 1; }
complete -r 2>/dev/null || true
# shellcheck disable=SC1090
source "$COMPLETION"
compopt() { :; } # only valid while bash itself completes

# complete WORD... : the candidates for the last word, one per line.
complete_words() {
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMPREPLY=()
    _swaywatch
    printf '%s\n' "${COMPREPLY[@]}" | sort
}
has() { # has CANDIDATE WORD...
    local want=$1
    shift
    complete_words "$@" | grep -qx -- "$want" || fail "'$*' does not offer '$want'"
}

commands=$("$SW" --help | awk '/^Commands:/ {on = 1; next}
    on && /^$/ {exit} on && /^  [a-z]/ {print $1}')
[ -n "$commands" ] || fail "no commands in swaywatch --help"
for c in $commands; do
    has "$c" swaywatch ""
    has --version swaywatch "$c" --
    has --help swaywatch "$c" --
    for o in $("$SW" "$c" --help | grep -oE -- '(^|[ ,])--[a-z][a-z0-9-]*' | sed 's/^[ ,]*//' | sort -u); do
        has "$o" swaywatch "$c" --
    done
done
has --version swaywatch --
[ "$(complete_words swaywatch si)" = simulate ] || fail "'si' does not complete to simulate"
has half-sine swaywatch simulate --pulse ""
has full-sine swaywatch simulate --pulse f
has rk8pd swaywatch replay --scheme rk
has g swaywatch replay --accel-unit ""
has m/s2 swaywatch boundary --units ""
has gtan swaywatch boundary --units gt
has frame.zeta= swaywatch replay --set frame.z
has replay swaywatch batch --job ""
[ -z "$(complete_words swaywatch batch --threads "")" ] || fail "batch --threads offers something"

if printf '%s\n' "$commands" | grep -qx watch; then
    has SWAY_STATE swaywatch watch --state-channel ""
    has SWAY_ALARM swaywatch watch --alarm-channel S
    has --once swaywatch watch --o
    [ -z "$(complete_words swaywatch watch --wait "")" ] || fail "watch --wait offers something"
fi

cd "$T/work"
touch scenes/crate.ini scenes/notes.txt drive.csv fleet.jsonl
has scenes/crate.ini swaywatch replay --scene scenes/
if complete_words swaywatch replay --scene scenes/ | grep -q notes.txt; then
    fail "--scene offers a file that is not .ini"
fi
touch fig.png fig.svg fig.jpg
has fig.png swaywatch replay drive.csv --plot fig
has fig.svg swaywatch simulate --plot fig
if complete_words swaywatch replay --plot fig | grep -q fig.jpg; then
    fail "--plot offers a file that is neither .png nor .svg"
fi
has drive.csv swaywatch replay --wide d
has scenes swaywatch simulate -s sc
has drive.csv swaywatch replay d
has fleet.jsonl swaywatch batch --out f
has drive.csv swaywatch batch --csv d
echo "completion.sh: ok ($(echo $commands | wc -w) commands)"
