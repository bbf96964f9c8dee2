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
for opt in --pulse --amplitude --amplitude-g --omega --duration --sample-interval rad/s; do
    grep -q -- "$opt" "$TMP/out" || fail "simulate --help: $opt not listed"
done
echo "ok"
