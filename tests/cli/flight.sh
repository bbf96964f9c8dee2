#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A vertical jolt (physics.md, "Free flight").  The hard stop of
# sample_logs/hard-stop-overturn.csv with a vertical channel that reads
# -12 m/s^2 for one 1 ms sample at 3.3 s, while the crate rocks toward
# its overturn: the bed falls faster than gravity for a third of a
# millisecond.  That reset the crate to rest as a model fault and lost
# the overturn ("unreliable", exit 2 with --fail-on-overturn); a short
# flight keeps its momentum, and the crate overturns as without the
# jolt (within 1 ms), exit 1.  A flight of over 0.1 s leaves the verdict
# incomplete, said in the JSON and the summary.
. "$(dirname "$0")/lib.sh"

SCENE="$SRC/sample_logs/crate.ini"
python3 - "$SRC/sample_logs/hard-stop-overturn.csv" "$TMP" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))[1:]
with open(sys.argv[2] + "/jolt.csv", "w") as j, open(sys.argv[2] + "/long.csv", "w") as l:
    j.write("t_s,accel_mps2,vert_mps2\n")
    l.write("t_s,accel_mps2,vert_mps2\n")
    for t, a in rows:
        x = float(t)
        j.write("%s,%s,%g\n" % (t, a, -12.0 if abs(x - 3.3) < 1e-9 else 0.0))
        l.write("%s,%s,%g\n" % (t, a, -2 * 9.81 if 1.0 <= x <= 1.2 else 0.0))
PY
run "$SW" replay "$SRC/sample_logs/hard-stop-overturn.csv" --scene "$SCENE" --reserve-rate 0 --json
expect_rc 0 "without the jolt"
cp "$TMP/out" "$TMP/plain.json"
run "$SW" replay "$TMP/jolt.csv" --scene "$SCENE" --vert-col 3 --vert-excludes-gravity \
    --reserve-rate 0 --json --fail-on-overturn
expect_rc 1 "a 1 ms jolt while rocking"
python3 - "$TMP/out" "$TMP/plain.json" <<'PY' || fail "the jolt changed the verdict"
import json, sys
p, q = (json.load(open(f))["packages"][0] for f in sys.argv[1:3])
print("overturn %.6f s, without the jolt %.6f s; %d flight of %.4f s"
      % (p["overturn_time"], q["overturn_time"], p["flights"], p["flight_max"]), file=sys.stderr)
assert p["verdict"] == "overturned" and p["faults"] == 0, p
assert p["flights"] == 1 and p["flight_max"] < 0.1 and p["flight_long_time"] is None, p
assert abs(p["overturn_time"] - q["overturn_time"]) < 1e-3, (p["overturn_time"], q["overturn_time"])
assert "flights" not in q, q
PY
run "$SW" replay "$TMP/long.csv" --scene "$SCENE" --vert-col 3 --vert-excludes-gravity \
    --reserve-rate 0 --json
expect_rc 0 "a long flight"
json_check "$TMP/out" 'j["packages"][0]["verdict"] == "incomplete" and j["packages"][0]["faults"] == 0'
json_check "$TMP/out" 'j["packages"][0]["flight_max"] > 0.1 and abs(j["packages"][0]["flight_long_time"] - 1.0) < 2e-3'
run "$SW" replay "$TMP/long.csv" --scene "$SCENE" --vert-col 3 --vert-excludes-gravity --reserve-rate 0
grep -q "INCOMPLETE: in the air over 0.1 s" "$TMP/out" || {
    show
    fail "the summary does not say the verdict is incomplete"
}
echo "flight: ok"
