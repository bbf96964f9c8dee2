#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# One input path: the same samples - a hard stop that overturns the crate,
# with a 10 ms spike of -900 m/s^2 and a 0.5 s hole - as a CSV log
# replayed, as an lcm-logger file replayed (publishing), and pushed message
# by message into the monitor core (sw_lcm_tool feed: its push API, read
# with LCM's own reader, no network) go through the same input stream, so
#   - the states are the same, byte for byte, in all three;
#   - the two replays write the same events;
#   - the monitor core pushed by hand publishes exactly what the lcm-logger
#     replay published (every alarm, with its utime; the states);
#   - its package alarms (uplift, tip, overturned, rest, without a rate
#     limit) are the CSV replay's events of those kinds, at the same times.
# usage: one_path.sh SWAYWATCH SW_LCM_TOOL SOURCE_DIR PYTHONPATH
set -eu
SW=$1 TOOL=$2 SRC=$3 PYDIR=$4
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "one_path.sh: FAIL: $*" >&2
    exit 1
}
S1=$SRC/sample_logs/crate.ini
S2=$SRC/sample_logs/crate-on-frame.ini

python3 - "$SRC/sample_logs/hard-stop-overturn.csv" "$T/drive.csv" <<'PY'
import sys
rows = [l.strip().split(",") for l in open(sys.argv[1])][1:]
out = ["t_s,accel_mps2"]
for t, a in rows:
    tt = float(t)
    if 5.5 < tt < 6.0:
        continue  # the hole
    out.append("%s,%s" % (t, "-900" if 1.0 <= tt < 1.01 else a))
open(sys.argv[2], "w").write("\n".join(out) + "\n")
PY
PYTHONPATH=$PYDIR python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/drive.csv" "$T/drive.lcmlog" \
    --start-utime 1700000000000000 >/dev/null

"$SW" replay "$T/drive.csv" --scene "$S1" --scene "$S2" --out "$T/csv.states" \
    --events "$T/csv.events" --all-impacts -q 2>"$T/csv.err" || fail "CSV replay: $(cat "$T/csv.err")"
"$SW" replay "$T/drive.lcmlog" --scene "$S1" --scene "$S2" --out "$T/lcm.states" \
    --events "$T/lcm.events" --all-impacts -q --publish "file://$T/pub.lcmlog?mode=w" --speed 0 \
    2>"$T/lcm.err" || fail "lcm-logger replay: $(cat "$T/lcm.err")"
"$TOOL" feed --publish "file://$T/core.lcmlog?mode=w" "$T/drive.lcmlog" "$S1" "$S2" \
    >"$T/core.txt" || fail "sw_lcm_tool feed"
"$TOOL" feed --all-alarms "$T/drive.lcmlog" "$S1" "$S2" >"$T/all.txt" ||
    fail "sw_lcm_tool feed --all-alarms"

# the drive did what it should: the spike refused, rocking, an overturn
grep -q '10 rejected rows' "$T/csv.err" || fail "the spike was not refused: $(cat "$T/csv.err")"
grep -q 'crate-A-on-frame,uplift' "$T/csv.events" || fail "the frame did not rock"
grep -q 'crate-A,overturn' "$T/csv.events" || fail "no overturn in the drive"

# 1. states, byte for byte
[ "$(wc -l <"$T/csv.states")" -gt 14000 ] || fail "too few states"
cmp "$T/csv.states" "$T/lcm.states" || fail "CSV and lcm-logger replays' states differ"
tail -n +2 "$T/csv.states" >"$T/csv.rows"
sed -n 's/^state //p' "$T/core.txt" >"$T/core.rows"
cmp "$T/csv.rows" "$T/core.rows" || fail "the monitor core's states differ from the CSV replay's"

# 2. events
cmp "$T/csv.events" "$T/lcm.events" || fail "CSV and lcm-logger replays' events differ"

# 3. what is published
"$TOOL" dump "$T/pub.lcmlog" >"$T/pub.txt"
"$TOOL" dump "$T/core.lcmlog" >"$T/core.dump"
grep -q '^alarm .* crate-A 6 ' "$T/pub.txt" || fail "no OVERTURNED alarm published"
diff "$T/pub.txt" "$T/core.dump" || fail "the replay and the monitor core publish differently"

# 4. package alarms are the CSV replay's events
python3 - "$T/csv.events" "$T/all.txt" <<'PY' || fail "alarms and events disagree"
import csv, sys
kinds = {"uplift": "uplift", "tip": "tip", "overturn": "overturned", "rest": "rest"}
with open(sys.argv[1]) as f:
    ev = [(r["t"], r["package"], kinds[r["event"]]) for r in csv.DictReader(f)
          if r["event"] in kinds]
al = []
for line in open(sys.argv[2]):
    if line.startswith("alarm "):
        _, t, name, kind = line.split()
        if kind in kinds.values():
            al.append((t, name, kind))
assert ev, "no events"
assert ev == al, (ev[:5], al[:5])
print("ok:", len(ev), "package events and alarms agree")
PY
echo "ok: CSV replay, lcm-logger replay and the monitor core: one path"
