#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# swaywatch watch, in a terminal (tmux) and as a plain snapshot, against a
# monitor fed by lcm-logplayer (a braking pulse that rocks the crate):
#  - the screen shows the package, a bar of |theta|/alpha that fills while
#    the crate rocks (alpha from --scene), the input line and the alarms,
#    newest first (the critical margin alarm among them);
#  - after a resize the view is drawn again within the new width;
#  - 'q' quits with exit 0;
#  - --once without --scene (alpha inferred from the bare crate's states)
#    prints one snapshot with the same facts on stdout and exits 0.
# usage: udpm_watch.sh SWAYWATCH SW_LCM_TOOL SCENE PORT
set -eu
# Without a network namespace: skipped (77), saying so.
NETNS_SKIP=1
export NETNS_SKIP
. "$(dirname "$0")/netns.sh"
SW=$1 TOOL=$2 SCENE=$3 PORT=$4
URL="udpm://239.255.76.67:$PORT?ttl=0&recv_buf_size=2097152"
command -v tmux >/dev/null 2>&1 || { echo "udpm_watch.sh: no tmux: skipped"; exit 77; }
TM="tmux -S $T/tmux.sock -f /dev/null"
cleanup_tmux() { $TM kill-server 2>/dev/null || true; }
trap 'cleanup_tmux; cleanup' EXIT

screen() { $TM capture-pane -p -t w >"$T/screen.txt"; }

"$TOOL" mklog "$T/accel.lcmlog" --rate 500 --duration 4
"$SW" monitor -l "$URL" --scene "$SCENE" 2>"$T/monitor.err" &
MON=$!
PIDS="$PIDS $MON"
export TERM=xterm
$TM new-session -d -s w -x 110 -y 30 \
    "'$SW' watch -l '$URL' --scene '$SCENE' --alarms 20 2>'$T/watch.err'; echo \$? >'$T/watch.rc'"
"$SW" watch -l "$URL" --once --wait 6 >"$T/once.txt" 2>"$T/once.err" &
ONCE=$!
PIDS="$PIDS $ONCE"
wait_subscribed 6 # the monitor and two watches

lcm-logplayer --lcm-url="$URL" "$T/accel.lcmlog" >/dev/null &
PLAYER=$!
PIDS="$PIDS $PLAYER"
# While it plays: the bar fills as the crate rocks.
filled=0
n=0
while kill -0 "$PLAYER" 2>/dev/null && [ "$n" -lt 100 ]; do
    screen
    if grep -Eq '^crate-A +bare +rocking +\[#{3,}' "$T/screen.txt"; then
        filled=1
        cp "$T/screen.txt" "$T/rocking.txt"
    fi
    n=$((n + 1))
    sleep 0.1
done
wait "$PLAYER" || fail "lcm-logplayer failed"
[ "$filled" = 1 ] || { cat "$T/screen.txt"; fail "the bar never filled while the crate rocked"; }
cat "$T/rocking.txt"

# After it: the alarms, the sensor gap the monitor reported at the end.
n=0
until screen && grep -q 'sensor_gap' "$T/screen.txt"; do
    n=$((n + 1))
    [ "$n" -le 50 ] || { cat "$T/screen.txt"; fail "no sensor_gap alarm on the screen"; }
    sleep 0.1
done
cat "$T/screen.txt"
grep -q '^swaywatch watch ' "$T/screen.txt" || fail "no title"
# (a loaded machine may lose states on the way, and see a gap mid-play:
# counted, not failed)
grep -Eq '^input: [0-9.]+ states/s, lag [0-9.]+ days, rejected 0, gaps [1-9][0-9]*, lost [0-9]+ states [0-9]+ alarms' \
    "$T/screen.txt" || fail "input line"
grep -Eq '^crate-A +bare +(stuck|rocking) +\[[#.|]+\] +0\.[0-9]{2} ' "$T/screen.txt" ||
    fail "package line with a bar"
grep -Eq '^[0-9:.]+Z critical +crate-A +critical +margin [0-9.]+ < critical' "$T/screen.txt" ||
    fail "no critical alarm line"
grep -Eq '^[0-9:.]+Z info +crate-A +uplift' "$T/screen.txt" || fail "no uplift alarm line"
# newest first: the gap (last raised) above the uplift (first)
gap_at=$(grep -n 'sensor_gap' "$T/screen.txt" | head -1 | cut -d: -f1)
up_at=$(grep -n ' uplift ' "$T/screen.txt" | head -1 | cut -d: -f1)
[ "$gap_at" -lt "$up_at" ] || fail "alarms not newest first"

# A smaller terminal: drawn again within it.
$TM resize-window -t w -x 72 -y 16
sleep 0.6
screen
cat "$T/screen.txt"
if awk 'length($0) > 72 { bad = 1 } END { exit !bad }' "$T/screen.txt"; then
    fail "lines wider than the resized terminal"
fi
grep -Eq '^crate-A +[a-z]+ +\[[#.|]{8,}\] +0\.[0-9]{2} ' "$T/screen.txt" || fail "no bar after the resize"
[ "$(wc -l <"$T/screen.txt")" -le 16 ] || fail "more rows than the resized terminal"

$TM send-keys -t w q
n=0
until [ -s "$T/watch.rc" ]; do
    n=$((n + 1))
    [ "$n" -le 50 ] || fail "'q' did not end watch"
    sleep 0.1
done
[ "$(cat "$T/watch.rc")" = 0 ] || { cat "$T/watch.err"; fail "watch exited with $(cat "$T/watch.rc")"; }

wait "$ONCE" || fail "watch --once exited with $?"
cat "$T/once.txt"
[ ! -s "$T/once.err" ] || { cat "$T/once.err"; fail "watch --once wrote to stderr"; }
grep -Eq '^crate-A +bare +[a-z]+ +\[[#|]' "$T/once.txt" ||
    fail "--once: no bar from the inferred alpha"
grep -Eq '^[0-9:.]+Z critical +crate-A +critical' "$T/once.txt" || fail "--once: no alarm line"
[ "$(grep -c '^swaywatch watch ' "$T/once.txt")" = 1 ] || fail "--once: not one snapshot"
kill -INT "$MON"
wait "$MON" || fail "monitor exited with $?"
echo "ok: watch on a terminal and as a snapshot"
