# SPDX-License-Identifier: GPL-3.0-or-later
# help.sh - every command answers --help on stdout with exit 0, and lists
# its options, units and exit codes.
. "$(dirname "$0")/lib.sh"

run "$SW" --help
expect_rc 0 "swaywatch --help"
grep -q '^usage: swaywatch' "$TMP/out" || fail "swaywatch --help: no usage line"
[ ! -s "$TMP/err" ] || fail "swaywatch --help wrote to stderr"

for cmd in replay simulate; do
    for h in --help -h; do
        run "$SW" "$cmd" "$h"
        expect_rc 0 "$cmd $h"
        [ ! -s "$TMP/err" ] || fail "$cmd $h wrote to stderr"
        grep -q "^usage: swaywatch $cmd" "$TMP/out" || fail "$cmd $h: no usage line"
        grep -q 'Exit codes: 0 ok' "$TMP/out" || fail "$cmd $h: no exit codes"
        for opt in --scene --set --scheme --dt --out --every --events --json --fail-on-overturn; do
            grep -q -- "$opt" "$TMP/out" || fail "$cmd $h: $opt not listed"
        done
    done
done
run "$SW" replay --help
for opt in --time-col --accel-col --vert-col --delimiter --no-header --accel-unit --time-unit \
    --flip --strict --settle m/s2; do
    grep -q -- "$opt" "$TMP/out" || fail "replay --help: $opt not listed"
done
run "$SW" simulate --help
for opt in --pulse --amplitude --amplitude-g --pulse-duration --omega --duration --sample-interval \
    rad/s 10g 11ms; do
    grep -q -- "$opt" "$TMP/out" || fail "simulate --help: $opt not listed"
done
# "swaywatch help CMD" is "swaywatch CMD --help" (as git does), on stdout
# with exit 0; "swaywatch help" is "swaywatch --help".
"$SW" --help >"$TMP/main" 2>/dev/null
run "$SW" help
expect_rc 0 "swaywatch help"
cmp -s "$TMP/out" "$TMP/main" || fail "swaywatch help differs from swaywatch --help"
for cmd in $(awk '/^Commands:/ {on = 1; next} on && /^$/ {exit} on {print $1}' "$TMP/main"); do
    "$SW" "$cmd" --help >"$TMP/want" 2>/dev/null
    run "$SW" help "$cmd"
    expect_rc 0 "swaywatch help $cmd"
    [ ! -s "$TMP/err" ] || fail "swaywatch help $cmd wrote to stderr"
    cmp -s "$TMP/out" "$TMP/want" || fail "swaywatch help $cmd differs from $cmd --help"
done
# Every command's help has one Output section, where --help itself is.
for cmd in $(awk '/^Commands:/ {on = 1; next} on && /^$/ {exit} on {print $1}' "$TMP/main"); do
    run "$SW" "$cmd" --help
    n=$(grep -c '^Output' "$TMP/out" || true)
    [ "$n" -eq 1 ] || fail "$cmd --help: $n Output sections, expected 1"
    sed -n '/^Output/,/^$/p' "$TMP/out" | grep -q -- '-h, --help' ||
        fail "$cmd --help: --help is not in the Output section"
done

# The accel channel has one name in replay and monitor (LCM builds):
# --accel-channel; replay's old --channel still works, unlisted.
if grep -q '^  monitor ' "$TMP/main"; then
    for cmd in replay monitor; do
        run "$SW" "$cmd" --help
        grep -q -- '--accel-channel ' "$TMP/out" || fail "$cmd --help: no --accel-channel"
        if grep -q -- ' --channel ' "$TMP/out"; then fail "$cmd --help lists --channel"; fi
    done
    printf '0,0\n0.001,0\n' >"$TMP/x.csv"
    for opt in --accel-channel --channel; do
        run "$SW" replay "$TMP/x.csv" --scene "$SRC/sample_logs/crate.ini" "$opt" ACCEL
        expect_rc 2 "replay $opt on a CSV log"
        expect_err "'$opt' is for lcm-logger files" "replay $opt on a CSV log"
    done
fi

# --version, as GNU tools print it: the version on the first line (scripts
# and help2man read it there), then the copyright and the licence; the same
# for every command.  The licence is the one in LICENSE.
grep -q 'GNU GENERAL PUBLIC LICENSE' "$SRC/LICENSE" && grep -q 'Version 3' "$SRC/LICENSE" ||
    fail "LICENSE is not the GPL version 3"
for args in "--version" "-V" "replay --version" "simulate --scene x --version"; do
    # shellcheck disable=SC2086
    run "$SW" $args
    expect_rc 0 "swaywatch $args"
    [ ! -s "$TMP/err" ] || fail "swaywatch $args wrote to stderr"
    [ "$(wc -l <"$TMP/out")" -eq 5 ] || { show; fail "swaywatch $args: not 5 lines"; }
    case $args in
    -*) head -1 "$TMP/out" | grep -Eqx 'swaywatch [0-9]+\.[0-9]+\.[0-9]+' ||
        fail "swaywatch $args: first line $(head -1 "$TMP/out")" ;;
    *) head -1 "$TMP/out" | grep -Eqx "swaywatch ${args%% *} [0-9]+\.[0-9]+\.[0-9]+" ||
        fail "swaywatch $args: first line $(head -1 "$TMP/out")" ;;
    esac
    sed -n 2p "$TMP/out" | grep -Eqx 'Copyright \(C\) 20[0-9][0-9] .+' || fail "$args: copyright line"
    for want in 'License GPLv3+: GNU GPL version 3 or later <https://gnu.org/licenses/gpl.html>' \
        'This is free software: you are free to change and redistribute it.' \
        'There is NO WARRANTY, to the extent permitted by law.'; do
        grep -qxF "$want" "$TMP/out" || fail "swaywatch $args lacks '$want'"
    done
done
if [ -w /dev/full ]; then
    run sh -c '"$1" --version >/dev/full' sh "$SW"
    expect_rc 3 "--version into a full disk"
    expect_prefixed_err "--version into a full disk"
fi

run "$SW" help no-such-command
expect_rc 2 "help of an unknown command"
expect_prefixed_err "help of an unknown command"
run "$SW" help replay simulate
expect_rc 2 "help of two commands"
echo "ok"
