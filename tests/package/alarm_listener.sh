#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# docs/examples/alarm_listener.c receives and prints the alarms swaywatch
# publishes over UDP multicast: in a private network namespace (only
# loopback, with the multicast route LCM needs), the listener runs while
# 'swaywatch replay --publish' replays a braking pulse; it must print every
# alarm that the same replay writes to a log file, in the same order, each
# stamped with its utime as ISO 8601 UTC to the millisecond, and named by
# its kind (the reserve's alarms too: they were printed as '?').
# Needs a network namespace (root, or user namespaces): exits 77 otherwise.
# usage: alarm_listener.sh SWAYWATCH LISTENER SOURCE_DIR PYTHON_TYPES_DIR
set -eu
NETNS_SKIP=1
. "$(dirname "$0")/../netns_enter.sh"

SW=$1 LISTENER=$2 SRC=$3 PYDIR=$4
T=$(mktemp -d)
pid=""
trap '[ -z "$pid" ] || kill "$pid" 2>/dev/null; rm -rf "$T"' EXIT
fail() { echo "alarm_listener.sh: $*" >&2; exit 1; }
export PYTHONPATH="$PYDIR"
URL="udpm://239.255.76.67:7667?ttl=0"

# The pulse starts after a second of still bed: LCM has no handshake, and a
# busy machine may take a moment to start the listener's receive thread.
# The pulse is across the truck (accel_t.ay) and the crate has a depth: its
# lateral plane's alarms are marked sideways, its longitudinal plane's not.
python3 "$SRC/tests/package/mkaccel.py" "$T/accel.lcmlog" --amplitude -5 --omega 10 \
    --duration 3 --lead 1 --lateral
cat >"$T/crate.ini" <<INI
[package]
name = crate-A
height = 2.0
width = 0.728
depth = 0.728
mass = 1000
[alarm]
warn_reserve_g = 2.0
critical_reserve_g = 1.0
INI

# The alarms, as a log file.
"$SW" replay "$T/accel.lcmlog" --scene "$T/crate.ini" --quiet --speed 0 \
    --publish "file://$T/alarms.lcmlog?mode=w"
python3 - "$T/alarms.lcmlog" >"$T/expected" <<'PY'
import datetime, struct, sys
from swaywatch import alarm_t
f = open(sys.argv[1], "rb")
while (h := f.read(28)) and len(h) == 28:
    _, _, _, cl, dl = struct.unpack(">IqqII", h)
    ch, data = f.read(cl).decode(), f.read(dl)
    if ch == "SWAY_ALARM":
        a = alarm_t.decode(data)
        t = datetime.datetime.fromtimestamp(a.utime // 1000000, datetime.timezone.utc)
        kinds = {v: k[5:] for k, v in vars(alarm_t).items() if k.startswith("KIND_")}
        print(a.seq, kinds[a.kind], "%s.%03dZ" % (t.strftime("%Y-%m-%dT%H:%M:%S"), a.utime % 1000000 // 1000),
              "sideways" if a.plane == alarm_t.PLANE_LATERAL else "-")
PY
n=$(wc -l <"$T/expected")
[ "$n" -ge 3 ] || fail "the replay raised only $n alarms"

# The same alarms, live.  Real-time speed: the listener keeps up easily.
"$LISTENER" -l "$URL" -n "$n" -t 10 >"$T/printed" 2>"$T/listener.err" &
pid=$!
i=0
until grep -q listening "$T/listener.err"; do
    i=$((i + 1))
    [ $i -lt 100 ] || fail "the listener did not start"
    sleep 0.05
done
sleep 0.3
"$SW" replay "$T/accel.lcmlog" --scene "$T/crate.ini" --quiet --speed 1 --publish "$URL"
wait "$pid" || fail "the listener failed"
pid=""
cat "$T/printed"
[ "$(wc -l <"$T/printed")" -eq "$n" ] || fail "printed $(wc -l <"$T/printed") alarms, expected $n"
# seq and kind of every alarm, in order (kind by name in the printout).
awk '{print $3}' "$T/printed" >"$T/seqs"
awk '{print $1}' "$T/expected" | diff - "$T/seqs" >/dev/null || fail "seq numbers differ"
# The time of each: ISO 8601 UTC with milliseconds, that of the alarm's utime.
awk '{print $1}' "$T/printed" >"$T/times"
awk '{print $3}' "$T/expected" | diff - "$T/times" >/dev/null ||
    fail "times differ from the alarms' utime: $(head -n 2 "$T/times" | tr '\n' ' ')"
grep -Eqv '^[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}\.[0-9]{3}Z seq ' "$T/printed" &&
    fail "a line without an ISO 8601 time: $(grep -Ev '^[0-9-]{10}T' "$T/printed" | head -n 1)"
awk '{print $5}' "$T/printed" >"$T/kinds"
awk '{print $2}' "$T/expected" | diff - "$T/kinds" >/dev/null ||
    fail "kinds differ: $(paste "$T/kinds" "$T/expected" | head -n 5 | tr '\n' ';')"
grep -q 'UPLIFT' "$T/printed" || fail "no UPLIFT alarm printed"
grep -q 'RESERVE_WARN' "$T/printed" || fail "no RESERVE_WARN alarm printed"
grep -q 'crate-A' "$T/printed" || fail "no package name printed"
# The plane: "sideways" after the name exactly where the alarm is lateral.
awk '{print $7 == "sideways" ? "sideways" : "-"}' "$T/printed" >"$T/planes"
awk '{print $4}' "$T/expected" | diff - "$T/planes" >/dev/null ||
    fail "planes differ: $(paste "$T/planes" "$T/expected" | head -n 5 | tr '\n' ';')"
grep -q 'sideways' "$T/planes" || fail "no lateral alarm printed"
grep -q -- '^-$' "$T/planes" || fail "no longitudinal (or input) alarm printed"
grep -q '0 lost' "$T/listener.err" || fail "the listener lost alarms: $(cat "$T/listener.err")"
echo "alarm_listener.sh: ok ($n alarms)"
