#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Integration, real LCM tools over UDP multicast: lcm-logger records a
# monitor session in which a sender publishes a braking pulse (with a
# wrong-type and a truncated message on the accel channel every 100
# samples).  Then `swaywatch replay` of the recording must give the same
# states and the same alarms as the monitor published live.
# usage: udpm_logger.sh SWAYWATCH SW_LCM_TOOL SCENE PORT
set -eu
. "$(dirname "$0")/netns.sh"
SW=$1 TOOL=$2 SCENE=$3 PORT=$4
URL="udpm://239.255.76.67:$PORT?ttl=0"

lcm-logger -q -f --lcm-url="$URL" "$T/rec.lcmlog" &
LOGGER=$!
PIDS="$LOGGER"
"$SW" monitor -l "$URL" --scene "$SCENE" --status 1 2>"$T/monitor.err" &
MON=$!
PIDS="$PIDS $MON"
wait_subscribed 4 # the logger and the monitor
"$TOOL" publish "$URL" --rate 500 --duration 3 --bad 100
wait_for "$T/monitor.err" 'accepted 1501, rejected 30'
sleep 0.4 # the logger's last messages, and the sensor-gap timer (0.1 s)
kill -INT "$MON"
wait "$MON" || fail "monitor exited with $?"
kill -INT "$LOGGER"
wait "$LOGGER" || true
cat "$T/monitor.err"

# Every message counted once; the bad ones refused, the monitor went on.
grep -q 'received 1531 = accepted 1501 + rejected 30 (decode 30); lost 0' "$T/monitor.err" ||
    fail "monitor counts"
grep -q 'swaywatch: monitor 1 s: ' "$T/monitor.err" || fail "no status line"

"$TOOL" dump "$T/rec.lcmlog" >"$T/live.txt"
replay_published "$T/rec.lcmlog"

grep -q '^accel 1531$' "$T/live.txt" || fail "logger did not record every accel message"
grep -q '^state crate-A count 1501 ' "$T/live.txt" || fail "not one state per sample"
grep -q '^state_seq_gaps 0$' "$T/live.txt" || fail "states lost on the way"
grep -q '^nonfinite 0$' "$T/live.txt" || fail "non-finite value published"
grep -q 'no accel sample for' "$T/live.txt" || fail "no SENSOR_GAP alarm after the sender stopped"
# The summary's peak (over the integration steps) agrees with the peak of
# the published states (at the samples) to the resolution of 2 ms samples.
same_physics '^alarm .* 4 2 margin' "the pulse should reach the critical margin"
echo "ok: live monitor == replay of its recording (peak theta $peak rad)"
