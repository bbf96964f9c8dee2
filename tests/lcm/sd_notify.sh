#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The monitor under systemd's notification protocol (sd_notify(3)), with a
# stand-in for systemd's socket (notify_recv.py; systemd itself does not run
# here).  The monitor listens on memq:// (in-process, no network): its loop
# runs, nothing arrives.  Checks:
#  - READY=1 comes first, once, with a STATUS=;
#  - with WATCHDOG_USEC=400000 (a 0.4 s watchdog), WATCHDOG=1 comes at
#    least every 0.4 s and about every 0.2 s, from start to stop;
#  - --status lines become STATUS=;
#  - SIGHUP: RELOADING=1, then READY=1 again;
#  - SIGTERM: STOPPING=1 is the last message, exit 0;
#  - WATCHDOG_PID naming another process: no WATCHDOG=1 (the watchdog is
#    that process's), but READY=1 all the same;
#  - without NOTIFY_SOCKET the monitor runs as ever.
# Skipped (77) in a build without libsystemd.
# usage: sd_notify.sh SWAYWATCH SCENE HAVE_SYSTEMD
set -eu
SW=$1 SCENE=$2 HAVE=$3
HERE=$(cd "$(dirname "$0")" && pwd)
case "$HAVE" in
ON | on | 1 | TRUE | true) ;;
*) echo "sd_notify.sh: built without libsystemd: the monitor does not notify: skipped"; exit 77 ;;
esac
T=$(mktemp -d)
PIDS=""
cleanup() {
    for p in $PIDS; do kill "$p" 2>/dev/null || true; done
    rm -rf "$T"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# listen NAME: a receiver at $T/NAME.sock writing $T/NAME.txt
listen() {
    rm -f "$T/$1.ready"
    python3 "$HERE/notify_recv.py" "$T/$1.sock" "$T/$1.txt" "$T/$1.ready" 5 &
    PIDS="$PIDS $!"
    n=0
    until [ -e "$T/$1.ready" ]; do
        n=$((n + 1))
        [ "$n" -le 100 ] || fail "the receiver did not start"
        sleep 0.1
    done
}

# until_in FILE TEXT
until_in() {
    n=0
    until grep -qF -- "$2" "$1" 2>/dev/null; do
        n=$((n + 1))
        [ "$n" -le 200 ] || fail "no '$2' in $1 after 20 s"
        sleep 0.1
    done
}

# 1. The watchdog, status, reload and stop.
listen a
NOTIFY_SOCKET=$T/a.sock WATCHDOG_USEC=400000 \
    "$SW" monitor -l memq:// --scene "$SCENE" --status 0.3 2>"$T/a.err" &
MON=$!
PIDS="$PIDS $MON"
until_in "$T/a.txt" READY=1
sleep 1
kill -HUP "$MON"
until_in "$T/a.txt" RELOADING=1
# the reload reads the scene once it stayed unchanged for a second
until_in "$T/a.err" "reload: no scene changed"
sleep 0.3
kill -TERM "$MON"
rc=0
wait "$MON" || rc=$?
[ "$rc" -eq 0 ] || { cat "$T/a.err" >&2; fail "monitor exited with $rc"; }
until_in "$T/a.txt" STOPPING=1
cat "$T/a.txt"

python3 - "$T/a.txt" <<'PY' || fail "notifications (above)"
import sys
lines = [l.rstrip("\n").split(" ", 1) for l in open(sys.argv[1])]
t = [float(a) for a, _ in lines]
m = [b for _, b in lines]
def check(cond, what):
    if not cond:
        sys.exit("sd_notify.sh: " + what)
check(m[0].startswith("READY=1|STATUS=waiting for samples on ACCEL"), "READY=1 first, with STATUS=")
check(m[-1] == "STOPPING=1", "STOPPING=1 last")
pings = [ti for ti, mi in zip(t, m) if mi == "WATCHDOG=1"]
check(len(pings) >= 8, "%d WATCHDOG=1 in about 1.6 s, expected one every 0.2 s" % len(pings))
gaps = [b - a for a, b in zip(pings, pings[1:])]
check(max(gaps) < 0.4, "WATCHDOG=1 %.3f s apart: the 0.4 s watchdog would kill it" % max(gaps))
check(min(gaps) > 0.1, "WATCHDOG=1 %.3f s apart: more often than half the timeout" % min(gaps))
check(pings[-1] > t[0] + 1.2, "WATCHDOG=1 stopped early")
st = [mi for mi in m if mi.startswith("STATUS=monitor ") and "samples/s" in mi]
check(len(st) >= 3, "the --status lines as STATUS=")
r = m.index("RELOADING=1")
check("READY=1" in m[r + 1:], "READY=1 after RELOADING=1")
check(m.count("READY=1|STATUS=waiting for samples on ACCEL") == 1, "one READY=1 at start")
print("sd_notify.sh: %d pings, %.3f to %.3f s apart" % (len(pings), min(gaps), max(gaps)))
PY
grep -q 'swaywatch: monitor 0 s: ' "$T/a.err" || fail "--status line missing on stderr"

# 2. The watchdog of another process: not ours to ping.
listen b
NOTIFY_SOCKET=$T/b.sock WATCHDOG_USEC=400000 WATCHDOG_PID=1 \
    "$SW" monitor -l memq:// --scene "$SCENE" 2>"$T/b.err" &
MON=$!
PIDS="$PIDS $MON"
until_in "$T/b.txt" READY=1
sleep 0.8
kill -INT "$MON"
wait "$MON" || fail "monitor (b) exited with $?"
until_in "$T/b.txt" STOPPING=1
if grep -q WATCHDOG=1 "$T/b.txt"; then fail "WATCHDOG=1 sent for another process's watchdog"; fi

# 3. No service manager.
"$SW" monitor -l memq:// --scene "$SCENE" 2>"$T/c.err" &
MON=$!
PIDS="$PIDS $MON"
sleep 0.5
kill -INT "$MON"
wait "$MON" || fail "monitor without NOTIFY_SOCKET exited with $?"
grep -q 'monitor stopped (SIGINT)' "$T/c.err" || fail "no summary without NOTIFY_SOCKET"
echo "sd_notify.sh: ok"
