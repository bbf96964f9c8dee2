#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# 'swaywatch monitor' re-reads its scene files on SIGHUP without losing the
# state of the packages whose scene did not change.  In a private network
# namespace (udpm on loopback), two monitors watch the same two crates on
# the same samples: M gets SIGHUP after crate-B's file was edited (and a
# comment added to crate-A's), the reference R never does.  In the log
# lcm-logger records:
#   - crate-A of M equals crate-A of R, sample for sample, before and after
#     the reload (its state was kept: it was rocking at the reload);
#   - crate-B of M is at rest right after the reload while R's still rocks,
#     and rocks again in the next pulse (rebuilt from the new scene);
#   - M's state and alarm seq numbers go on across the reload (no restart),
#     up to the counts M reports;
#   - a reload with a broken scene file, or a FIFO in place of one, changes
#     nothing and M keeps running (the FIFO is refused without blocking).
# Needs a network namespace (root, or user namespaces): exits 77 otherwise.
# usage: sighup.sh SWAYWATCH SOURCE_DIR PYTHON_TYPES_DIR
set -eu
NETNS_SKIP=1
. "$(dirname "$0")/../netns_enter.sh"

SW=$1 SRC=$2 PYDIR=$3
command -v lcm-logger >/dev/null && command -v lcm-logplayer >/dev/null || {
    echo "sighup.sh: lcm-logger or lcm-logplayer missing (liblcm-bin): skipped"
    exit 77
}
T=$(mktemp -d)
PIDS=""
cleanup() {
    for p in $PIDS; do kill "$p" 2>/dev/null || true; done
    rm -rf "$T"
}
trap cleanup EXIT
fail() {
    echo "sighup.sh: $*" >&2
    for f in "$T"/*.err; do echo "--- $f" >&2; cat "$f" >&2; done
    exit 1
}
export PYTHONPATH="$PYDIR"
URL="udpm://239.255.76.67:7667?ttl=0"
RATE=200
# States at 50 Hz per package: less for the logger to keep up with on a
# busy machine (UDP drops silently).
MON_OPTS="-l $URL --state-rate 50"

crate() { # FILE NAME WIDTH
    printf '[package]\nname = %s\nheight = 2.0\nwidth = %s\nmass = 1000\n' "$2" "$3" >"$1"
}
mkdir -p "$T/m" "$T/r"
crate "$T/m/a.ini" crate-A 0.728
crate "$T/m/b.ini" crate-B 0.728
cp "$T/m/a.ini" "$T/m/b.ini" "$T/r/"

# Part 1: a braking pulse that leaves both crates rocking at its end
# (0.6 s); part 2 goes on from there with a harder pulse at 0.8 s.
python3 "$SRC/tests/package/mkaccel.py" "$T/part1.lcmlog" --rate $RATE --amplitude -5 \
    --duration 0.6 --lead 0.1 >/dev/null
python3 "$SRC/tests/package/mkaccel.py" "$T/part2.lcmlog" --rate $RATE --amplitude -6 \
    --start 0.605 --duration 1.4 --lead 0.2 >/dev/null

lcm-logger -q -f --lcm-url="$URL" "$T/bus.lcmlog" 2>"$T/logger.err" &
PIDS="$PIDS $!"
"$SW" monitor $MON_OPTS --scene "$T/m/a.ini" --scene "$T/m/b.ini" 2>"$T/m.err" &
M=$!
PIDS="$PIDS $M"
"$SW" monitor $MON_OPTS --scene "$T/r/a.ini" --scene "$T/r/b.ini" \
    --state-channel REF_STATE --alarm-channel REF_ALARM 2>"$T/r.err" &
R=$!
PIDS="$PIDS $R"
sleep 1 # LCM has no handshake: give the subscribers time to start

lcm-logplayer -s 1 -l "$URL" "$T/part1.lcmlog" >/dev/null 2>&1
sleep 0.3

# Reload: crate-B changes (narrower: it lifts more easily), crate-A gets
# only a comment.
crate "$T/m/b.ini" crate-B 0.6
printf '# checked on arrival\n' >>"$T/m/a.ini"
kill -HUP "$M"
i=0
until grep -q 'reload: .* rebuilt, the others kept' "$T/m.err"; do
    i=$((i + 1))
    [ $i -lt 100 ] || fail "no reload reported"
    sleep 0.05
done
grep -q 'reload: crate-B rebuilt' "$T/m.err" || fail "crate-B not rebuilt"
if grep -q 'reload: crate-A rebuilt' "$T/m.err"; then fail "crate-A rebuilt for a comment"; fi

lcm-logplayer -s 1 -l "$URL" "$T/part2.lcmlog" >/dev/null 2>&1
sleep 0.5

# A broken scene file: nothing changes, the monitor goes on.
printf '[package]\nname = crate-B\nheight = -2\n' >"$T/m/b.ini"
kill -HUP "$M"
i=0
until grep -q 'scene files not applied' "$T/m.err"; do
    i=$((i + 1))
    [ $i -lt 100 ] || fail "no refusal of the broken scene reported"
    sleep 0.05
done
kill -0 "$M" 2>/dev/null || fail "the monitor died on a broken scene file"

# A FIFO in place of a scene file: refused at once (opening it must not
# block the monitor until somebody writes to it), the monitor goes on.
rm -f "$T/m/b.ini"
mkfifo "$T/m/b.ini"
kill -HUP "$M"
i=0
until grep -q 'b.ini: a FIFO: a scene must be a regular file' "$T/m.err"; do
    i=$((i + 1))
    [ $i -lt 100 ] || fail "a FIFO scene blocked the reload"
    sleep 0.05
done
kill -0 "$M" 2>/dev/null || fail "the monitor died on a FIFO scene file"

kill -TERM "$M" "$R"
wait "$M" || fail "monitor M exit status $?"
wait "$R" || fail "monitor R exit status $?"
sleep 0.3
PIDS=$(echo "$PIDS" | sed "s/ $M//; s/ $R//")
kill -INT $PIDS 2>/dev/null || true
wait 2>/dev/null || true
PIDS=""

# Both monitors must have had every sample, or their crate-A cannot be
# compared: a sample lost on the way makes the run inconclusive.
for f in m r; do
    grep -q 'lost 0 (by seq)' "$T/$f.err" || {
        echo "sighup.sh: monitor $f lost samples on the way (busy machine): skipped"
        exit 77
    }
done
published() { sed -n "s/.*published \([0-9]*\) states.*, \([0-9]*\) alarms (.*/\\$1/p" "$T/m.err"; }
python3 - "$T/bus.lcmlog" "$(published 1)" "$(published 2)" <<'PY' || fail "no clean reload"
import struct, sys
from swaywatch import state_t, alarm_t

T0 = 1_700_000_000_000_000
states = {"SWAY_STATE": {}, "REF_STATE": {}}
seqs = {"SWAY_STATE": [], "SWAY_ALARM": []}
with open(sys.argv[1], "rb") as f:
    while (h := f.read(28)) and len(h) == 28:
        _, _, _, cl, dl = struct.unpack(">IqqII", h)
        ch, data = f.read(cl).decode(), f.read(dl)
        if ch in states:
            m = state_t.decode(data)
            name = bytes(b & 0xFF for b in m.name).split(b"\0")[0].decode()
            states[ch].setdefault(name, {})[m.utime] = m
        if ch in seqs:
            seqs[ch].append((state_t if ch == "SWAY_STATE" else alarm_t).decode(data).seq)

ok = True
def check(cond, what):
    global ok
    if not cond:
        ok = False
    print(("ok   " if cond else "FAIL ") + what)

M, R = states["SWAY_STATE"], states["REF_STATE"]
reload_us = T0 + 605000  # first sample after the reload
def first_after(d):
    later = [u for u in d if u >= reload_us]
    return d[min(later)] if later else None
for name in ("crate-A", "crate-B"):
    check(name in M and name in R, name + " seen from both monitors")
common = sorted(set(M["crate-A"]) & set(R["crate-A"]))
check(len(common) > 50, "%d states of crate-A in both" % len(common))
same = all(M["crate-A"][u].theta == R["crate-A"][u].theta and
           M["crate-A"][u].theta_dot == R["crate-A"][u].theta_dot for u in common)
check(same, "crate-A of M equals crate-A of R at every sample")
a0 = first_after(M["crate-A"])
check(a0 is not None and a0.phase == state_t.PHASE_ROCKING and a0.theta != 0.0,
      "crate-A still rocking right after the reload (state kept)")
b_before = [u for u in M["crate-B"] if u < reload_us]
check(b_before and M["crate-B"][max(b_before)].phase == state_t.PHASE_ROCKING,
      "crate-B rocking before the reload")
b0 = first_after(M["crate-B"])
check(b0 is not None and b0.phase == state_t.PHASE_STUCK and b0.theta == 0.0,
      "crate-B at rest right after the reload (rebuilt)")
rb0 = R["crate-B"].get(b0.utime) if b0 else None
check(rb0 is not None and rb0.theta != 0.0, "the reference's crate-B still rocking then")
check(any(s.phase == state_t.PHASE_ROCKING for u, s in M["crate-B"].items() if u > reload_us),
      "crate-B rocks again in the second pulse")
# The logger may miss a message (UDP); the seq must still rise across the
# reload without restarting and end at the count M reports.
for ch, s, n in (("SWAY_STATE", seqs["SWAY_STATE"], int(sys.argv[2])),
                 ("SWAY_ALARM", seqs["SWAY_ALARM"], int(sys.argv[3]))):
    check(len(s) > 0 and all(b > a for a, b in zip(s, s[1:])) and s[-1] == n - 1,
          "%s: %d of %d messages recorded, seq rising to %d" % (ch, len(s), n, n - 1))
sys.exit(0 if ok else 1)
PY
echo "sighup.sh: ok"
