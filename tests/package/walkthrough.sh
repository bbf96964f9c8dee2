#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The README's live walkthrough, shortened to a 3 s drive: the monitor and
# the example listener run, csv2lcmlog.py converts a CSV drive and
# lcm-logplayer plays it at once (as the README does it, '&&').  The
# monitor's status lines must show a lag of milliseconds, not the seconds
# between conversion and playing; the listener must print the alarms with
# ISO 8601 times of today.  In a private network namespace (only loopback,
# with LCM's multicast route): exits 77 without one, or without
# lcm-logplayer (liblcm-bin).
# usage: walkthrough.sh SWAYWATCH LISTENER SOURCE_DIR PYTHON_TYPES_DIR
set -eu
if ! command -v lcm-logplayer >/dev/null 2>&1; then
    echo "walkthrough.sh: no lcm-logplayer (liblcm-bin): skipped"
    exit 77
fi
NETNS_SKIP=1
. "$(dirname "$0")/../netns_enter.sh"

SW=$1 LISTENER=$2 SRC=$3 PYDIR=$4
T=$(mktemp -d)
mon="" lis=""
trap 'for p in $mon $lis; do kill "$p" 2>/dev/null || true; done; rm -rf "$T"' EXIT
fail() { echo "walkthrough.sh: $*" >&2; exit 1; }
export PYTHONPATH="$PYDIR"
cd "$T"

# 3 s at 1 kHz: a hard stop at 1 s (-12 m/s^2 half sine of 10 rad/s).
python3 - >drive.csv <<'PY'
import math
print("t_s,accel_mps2")
for i in range(3001):
    t = i / 1000
    a = -12 * math.sin(10 * (t - 1)) if 1 <= t <= 1 + math.pi / 10 else 0.0
    print("%.3f,%.6f" % (t, a))
PY

day0=$(date -u +%Y-%m-%d)
"$SW" monitor --scene "$SRC/sample_logs/crate.ini" --status 1 2>monitor.err &
mon=$!
"$LISTENER" >listener.out 2>listener.err &
lis=$!
i=0
until grep -q listening listener.err; do
    i=$((i + 1))
    [ $i -lt 100 ] || fail "the listener did not start"
    sleep 0.05
done
sleep 0.5
python3 "$SRC/docs/examples/csv2lcmlog.py" drive.csv drive.lcmlog &&
    lcm-logplayer drive.lcmlog >/dev/null
sleep 1.2
kill -INT $mon $lis
wait $mon || fail "the monitor failed: $(cat monitor.err)"
wait $lis || true
mon="" lis=""
cat monitor.err listener.out

# Status lines with samples: "..., lag 18.39 ms (max 26.40), ..."
lags=$(sed -n 's/.*samples\/s, lag \([0-9.]*\) ms (max \([0-9.]*\)).*/\1 \2/p' monitor.err)
[ -n "$lags" ] || fail "no status line with a lag"
echo "$lags" | awk '$1 > 0 || $2 > 0 { n++; if ($1 > 500) bad = 1 }
    END { exit !(n > 0 && !bad) }' || fail "lag of more than 500 ms: $(echo $lags)"
grep -q 'received 3001 = accepted 3001' monitor.err || fail "the monitor did not get all 3001 samples"
n=$(grep -c ' seq ' listener.out || true)
[ "$n" -ge 3 ] || fail "the listener printed $n alarms"
day1=$(date -u +%Y-%m-%d)
grep -Eq "^($day0|$day1)T[0-9:]{8}\.[0-9]{3}Z seq .* OVERTURNED " listener.out ||
    fail "no OVERTURNED alarm stamped today ($day1) in ISO 8601"
echo "walkthrough.sh: ok (lag $(echo "$lags" | awk '{print $1}' | tr '\n' ' ')ms; $n alarms)"
