#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# field.sh - the live monitor as a truck's computer runs it for months:
# one drive at 1 kHz over real LCM UDP multicast (loopback, in a private
# network namespace) with every field fault in it, and scene reloads all
# the while.
#
#   sh field.sh SWAYWATCH FEED SOURCE_DIR WORK_DIR PYTHON_TYPES_DIR [SECONDS]
#
# FEED is sw_accel_feed.  The drive (default 40 s of samples) carries 3 %
# garbage, the braking pulses that rock the crates, and these faults, each
# at its own time: a sample with seq INT64_MAX and later one with INT64_MIN;
# a forged sample a year ahead; samples stamped INT64_MAX and INT64_MIN; a
# sensor restart (seq from 0, time 30 s back); a clock step of an hour
# forward; a flood of 20,000 copies of one sample; a second of vertical
# acceleration below -1 g (the packages fly: a critical alarm each); a
# 2 s outage; 2 s of a forger sending a quiet sample stamped 2.5 ms ahead
# after every second genuine one; 2 s of samples read from an IMU's FIFO,
# 32 at a time, each stamped when read.  Meanwhile the monitor gets SIGHUP
# every 2 s, in turn with an unchanged scene file, a changed bare crate, a
# broken scene file, a FIFO in place of one, and the bare crate's file
# being rewritten in place (its first lines a valid scene of a package
# named after the file, the name 0.5 s after the SIGHUP), with a stiff
# cushion (adaptive scheme) beside the bare crate.  Asserted:
#   - the monitor never exits until SIGINT, and then exits 0;
#   - no half-written scene file is ever applied;
#   - after each fault, states of the samples after it are published within
#     RESUME samples (default 50: three to confirm, ten to the next state on
#     the 100 Hz grid, and room for the scheduler), plus as many as the
#     kernel dropped (the flood can overflow the socket: those samples
#     never reach the monitor);
#   - no state stops for longer than 2.5 s of wall time outside the outage
#     and the second of free fall (a blinded monitor is silent for good);
#   - every message is accounted for: received = accepted + rejected by
#     reason (nothing held after the stop), received = published less the
#     kernel's UDP drops, the refusals by reason those sent (the faults
#     included: jump, time, duplicate), lost by seq = the outage's samples
#     (plus drops and shed messages), never negative;
#   - no published number is non-finite;
#   - alarms are rate-limited: no package and kind has more than 8 in any
#     second (three, a summary, three), the storm was folded;
#   - the forger raised INPUT_CONTESTED (critical) and cost only its own
#     samples (every genuine one accepted); the FIFO reads raised at most
#     one SENSOR_GAP (the first batch, before its pace is known), no storm;
#   - memory stays flat: VmRSS at the end within SOAK_RSS_KB (default 4096:
#     LCM's receive ring may double once when the machine stalls) of VmRSS
#     after the first 10 s (skipped under AddressSanitizer, whose
#     quarantine grows by design; it checks leaks itself at exit).
# Exit 77 (skipped) when a private network namespace cannot be made.
set -eu
SW=$1
FEED=$2
SRC=$3
WORK=$4
PYDIR=$5
SECS=${6:-40}
RATE=1000
RESUME=${FIELD_RESUME_SAMPLES:-50}
RSS_BOUND=${SOAK_RSS_KB:-4096}

. "$(dirname "$0")/lcmtest.sh"
enter_netns "$@"
rm -rf "$WORK"
mkdir -p "$WORK/scenes"
URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
cp "$SRC/tests/scenes/crate-a-bare.ini" "$WORK/scenes/bare.ini"
cp "$SRC/tests/scenes/crate-a-stiff-cushion.ini" "$WORK/scenes/stiff.ini"
MON=""
LOGGER=""
HUPPER=""
cleanup() {
    [ -n "$HUPPER" ] && kill "$HUPPER" 2>/dev/null || true
    [ -n "$MON" ] && kill "$MON" 2>/dev/null || true
    [ -n "$LOGGER" ] && kill "$LOGGER" 2>/dev/null || true
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*" >&2
    tail -20 "$WORK/monitor.err" >&2
    exit 1
}

"$SW" monitor --scene "$WORK/scenes/bare.ini" --scene "$WORK/scenes/stiff.ini" \
    --lcm-url "$URL" --state-rate 100 --status 1 --vertical z --vert-excludes-gravity \
    2>"$WORK/monitor.err" &
MON=$!
lcm-logger --lcm-url="$URL" -c 'SWAY_.*' -q "$WORK/output.lcmlog" 2>"$WORK/logger.err" &
LOGGER=$!
wait_subscribed "$WORK/monitor.err"
kill -0 "$MON" || fail "the monitor did not start"

# SIGHUP every 2 s: unchanged, changed, broken, a FIFO; then back to good.
reloads() {
    i=0
    while kill -0 "$MON" 2>/dev/null; do
        sleep 2
        case $((i % 6)) in
        5)
            # rewritten in place, slowly: SIGHUP between the halves
            sed '/^name/d' "$WORK/scenes/bare.ini" >"$WORK/bare.body"
            grep '^name' "$WORK/scenes/bare.ini" >"$WORK/bare.name"
            {
                cat "$WORK/bare.body"
                sleep 0.5
                cat "$WORK/bare.name"
            } >"$WORK/scenes/bare.ini" &
            sleep 0.1
            ;;
        0) printf '# checked\n' >>"$WORK/scenes/bare.ini" ;;
        1) sed -i "s/^width .*/width = 0.7$((i / 6 % 3))/" "$WORK/scenes/bare.ini" ;;
        2) printf '[package]\nheight = -1\n' >"$WORK/scenes/stiff.ini" ;;
        3) rm -f "$WORK/scenes/stiff.ini" && mkfifo "$WORK/scenes/stiff.ini" ;;
        4) rm -f "$WORK/scenes/stiff.ini" &&
            cp "$SRC/tests/scenes/crate-a-stiff-cushion.ini" "$WORK/scenes/stiff.ini" ;;
        esac
        kill -HUP "$MON" 2>/dev/null || true
        i=$((i + 1))
    done
}
reloads &
HUPPER=$!

N=$((SECS * RATE))
at() { echo $(($1 * N / 40)); } # the faults at the same share of any length
utime=$(($(date +%s) * 1000000))
"$FEED" publish "$URL" --count "$N" --rate "$RATE" --garbage 30 --utime0 "$utime" --seed 7 \
    --event "$(at 5):seq:max" --event "$(at 7):future" \
    --event "$(at 9):utime:max" --event "$(($(at 9) + 500)):utime:min" \
    --event "$(at 11):restart:30" --event "$(at 15):step:3600" \
    --event "$(at 19):flood:20000" --event "$(at 23):fall:1" --event "$(at 27):pause:2" \
    --event "$(at 31):seq:min" --event "$(at 33):forge:2" --event "$(at 36):fifo:2" \
    >"$WORK/feed.txt" 2>"$WORK/feed.err" &
FEEDER=$!
sleep 10
rss_warm=$(rss_kb "$MON")
set +e
wait "$FEEDER"
frc=$?
set -e
[ "$frc" -eq 0 ] || fail "the feeder failed (status $frc): $(cat "$WORK/feed.err")"
kill -0 "$MON" 2>/dev/null || fail "the monitor died during the drive"
kill "$HUPPER" 2>/dev/null || true
wait "$HUPPER" 2>/dev/null || true
HUPPER=""
# the last reload may have left a FIFO or a broken file: put the scene back
rm -f "$WORK/scenes/stiff.ini"
cp "$SRC/tests/scenes/crate-a-stiff-cushion.ini" "$WORK/scenes/stiff.ini"
wait_idle "$WORK/monitor.err"
rss_end=$(rss_kb "$MON")
udp_drops=$(awk '/^Udp:/ && ++n == 2 { print $6 + $4 }' /proc/net/snmp)
kill -INT "$MON"
set +e
wait "$MON"
mon_rc=$?
set -e
MON=""
kill -INT "$LOGGER" 2>/dev/null || true
wait "$LOGGER" 2>/dev/null || true
LOGGER=""
"$FEED" check "$WORK/output.lcmlog" >"$WORK/output.txt"
# a half-written bare.ini has no name: applied, its package would be 'bare'
if grep -q 'reload: bare rebuilt' "$WORK/monitor.err"; then
    fail "a half-written scene file was applied"
fi
asan=0
ldd "$SW" 2>/dev/null | grep -q libasan && asan=1

export PYTHONPATH="$PYDIR"
python3 "$(dirname "$0")/field_check.py" "$WORK" "$mon_rc" "$rss_warm" "$rss_end" "$RSS_BOUND" \
    "$udp_drops" "$PROBES" "$RESUME" "$asan"
