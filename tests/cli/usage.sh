# SPDX-License-Identifier: GPL-3.0-or-later
# usage.sh - misuse is reported on stderr with the 'swaywatch: ' prefix and
# exit 2; unreadable files exit 3; bad scenes name FILE:LINE.
. "$(dirname "$0")/lib.sh"
SCENE=$SRC/sample_logs/crate.ini
LOG=$SRC/sample_logs/braking-pothole.csv

run "$SW" replay "$LOG" --scene "$SCENE" --no-such-option
expect_rc 2 "unknown long option"
expect_prefixed_err "unknown long option"
expect_err "--no-such-option" "unknown long option"
[ ! -s "$TMP/out" ] || fail "unknown option wrote to stdout"

run "$SW" simulate -Z
expect_rc 2 "unknown short option"
expect_prefixed_err "unknown short option"

run "$SW" replay "$LOG" --scene
expect_rc 2 "option without its value"
expect_prefixed_err "option without its value"

run "$SW" replay "$LOG" --scene "$SCENE" --json=yes
expect_rc 2 "value given to a flag"
expect_prefixed_err "value given to a flag"

run "$SW" replay "$LOG" --scene "$SCENE" --dt abc
expect_rc 2 "--dt abc"
expect_err "swaywatch: --dt: expected a positive number of seconds, got 'abc'" "--dt abc"
for bad in -1 0 nan inf 1e-3x ''; do
    run "$SW" replay "$LOG" --scene "$SCENE" --dt "$bad"
    expect_rc 2 "--dt '$bad'"
    expect_err "swaywatch: --dt: expected" "--dt '$bad'"
done

run "$SW" replay "$LOG" --scene "$SCENE" --scheme no-such-scheme
expect_rc 2 "--scheme no-such-scheme"
expect_err "rk4" "--scheme lists the valid names"

run "$SW" replay "$LOG" --scene "$SCENE" --accel-unit furlongs
expect_rc 2 "--accel-unit furlongs"
run "$SW" replay "$LOG" --scene "$SCENE" --time-unit h
expect_rc 2 "--time-unit h"
run "$SW" replay "$LOG" --scene "$SCENE" --delimiter '|'
expect_rc 2 "--delimiter |"
run "$SW" replay "$LOG" --scene "$SCENE" --time-col 0
expect_rc 2 "--time-col 0"
run "$SW" replay "$LOG" --scene "$SCENE" --settle -5
expect_rc 2 "--settle -5"
run "$SW" replay "$LOG" --scene "$SCENE" --every 0
expect_rc 2 "--every 0"
run "$SW" replay "$LOG" --scene "$SCENE" --set nodot
expect_rc 2 "--set without section.key=value"

run "$SW" replay --scene "$SCENE"
expect_rc 2 "replay without LOG"
expect_prefixed_err "replay without LOG"
run "$SW" replay "$LOG" "$LOG" --scene "$SCENE"
expect_rc 2 "replay with two LOGs"
run "$SW" replay "$LOG"
expect_rc 2 "replay without --scene"
expect_err "--scene" "replay without --scene"

run "$SW" simulate --scene "$SCENE" --pulse square --amplitude 5 --omega 3
expect_rc 2 "--pulse square"
run "$SW" simulate --scene "$SCENE" --pulse half-sine --omega 3
expect_rc 2 "simulate without amplitude"
expect_err "--amplitude" "simulate without amplitude"
run "$SW" simulate --scene "$SCENE" --pulse half-sine --amplitude 5 --omega -3
expect_rc 2 "--omega -3"

run "$SW" bogus-command
expect_rc 2 "unknown command"
expect_prefixed_err "unknown command"

# I/O: files that cannot be read.
run "$SW" replay "$TMP/no-such.csv" --scene "$SCENE"
expect_rc 3 "missing log"
expect_err "swaywatch: $TMP/no-such.csv: cannot open: No such file or directory" "missing log"
run "$SW" replay "$LOG" --scene "$TMP/no-such.ini"
expect_rc 3 "missing scene"
expect_err "$TMP/no-such.ini" "missing scene"
expect_err "No such file or directory" "missing scene"
run "$SW" replay "$LOG" --scene "$SCENE" --out "$TMP/no-such-dir/out.csv"
expect_rc 3 "--out into a missing directory"
expect_prefixed_err "--out into a missing directory"

# An output that would overwrite the log (or the other output) is refused.
cp "$LOG" "$TMP/log.csv"
run "$SW" replay "$TMP/log.csv" --scene "$SCENE" --out "$TMP/log.csv"
expect_rc 2 "--out naming the log"
expect_err "that is the log being read" "--out naming the log"
cmp -s "$LOG" "$TMP/log.csv" || fail "--out naming the log changed the log"
run "$SW" replay "$TMP/log.csv" --scene "$SCENE" --out "$TMP/x.csv" --events "$TMP/x.csv"
expect_rc 2 "--out and --events the same file"

# A scene must be a regular file: a FIFO is refused at once, without
# waiting for a writer (the run would hang otherwise: timeout 10).
mkfifo "$TMP/fifo.ini"
run timeout 10 "$SW" replay "$LOG" --scene "$TMP/fifo.ini"
expect_rc 2 "a FIFO as scene"
expect_err "$TMP/fifo.ini: a FIFO: a scene must be a regular file" "a FIFO as scene"
run "$SW" replay "$LOG" --scene "$TMP"
expect_rc 2 "a directory as scene"
expect_err "$TMP: a directory: a scene must be a regular file" "a directory as scene"

# Bad scenes: FILE:LINE: message.
cat >"$TMP/bad.ini" <<'INI'
[package]
name = crate
height = two metres
width = 0.728
mass = 1000
INI
run "$SW" replay "$LOG" --scene "$TMP/bad.ini"
expect_rc 2 "bad scene value"
expect_err "swaywatch: $TMP/bad.ini:3: " "bad scene value"
expect_prefixed_err "bad scene value"

cat >"$TMP/badkey.ini" <<'INI'
[package]
name = crate
height = 2.0
width = 0.728
mass = 1000
colour = red
INI
run "$SW" simulate --scene "$TMP/badkey.ini" --pulse half-sine --amplitude -8 --omega 3
expect_rc 2 "unknown scene key"
expect_err "swaywatch: $TMP/badkey.ini:6: " "unknown scene key"

run "$SW" replay "$LOG" --scene "$SCENE" --set package.height=-1
expect_rc 2 "--set making the scene invalid"
expect_prefixed_err "--set making the scene invalid"
run "$SW" replay "$LOG" --scene "$SCENE" --set package.nosuchkey=1
expect_rc 2 "--set of an unknown key"
expect_prefixed_err "--set of an unknown key"

# An lcm-logger file is recognised by its sync word (and needs LCM).
printf '\355\241\332\001not really an event log' >"$TMP/fake.lcmlog"
run "$SW" replay "$TMP/fake.lcmlog" --scene "$SCENE"
[ "$RC" -eq 2 ] || [ "$RC" -eq 3 ] || { show; fail "lcm-logger file: exit $RC"; }
expect_prefixed_err "lcm-logger file"
echo "ok"
