# SPDX-License-Identifier: GPL-3.0-or-later
# samples.sh - the sample logs give the outcomes sample_logs/README.md
# promises, and --fail-on-overturn turns an overturn into exit 1.
. "$(dirname "$0")/lib.sh"
LOGS=$SRC/sample_logs

run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$LOGS/crate.ini" --fail-on-overturn --json
expect_rc 0 "braking-pothole: the crate stays upright"
json_check "$TMP/out" 'not j["packages"][0]["overturned"] and j["packages"][0]["uplift_time"] is not None and j["packages"][0]["impacts"] > 0'

# The same drive overturns the crate on its soft frame (README's claim).
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$LOGS/crate-on-frame.ini" --json
expect_rc 0 "braking-pothole on the frame"
json_check "$TMP/out" 'j["packages"][0]["model"] == "frame" and j["packages"][0]["overturned"]'

run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$LOGS/crate.ini" --fail-on-overturn --json
expect_rc 1 "hard-stop-overturn: the crate overturns"
json_check "$TMP/out" 'j["packages"][0]["overturned"] and j["packages"][0]["overturn_time"] > j["packages"][0]["tip_time"] > j["packages"][0]["uplift_time"]'

# Without --fail-on-overturn an overturn is a result, not a failure.
run "$SW" replay "$LOGS/hard-stop-overturn.csv" --scene "$LOGS/crate.ini"
expect_rc 0 "hard-stop-overturn without --fail-on-overturn"
grep -q 'OVERTURNED at' "$TMP/out" || { show; fail "human summary does not say OVERTURNED"; }

# The human summary of the demo: both packages, every promised line.
run "$SW" replay "$LOGS/braking-pothole.csv" --scene "$LOGS/crate.ini" --scene "$LOGS/crate-on-frame.ini"
expect_rc 0 "demo replay"
# stderr says how the log was read, and nothing else
[ "$(cat "$TMP/err")" = "swaywatch: $LOGS/braking-pothole.csv: time: column 1 \"t_s\", s (from the header); accel: column 2 \"accel_mps2\", m/s^2 (from the header)" ] ||
    { show; fail "demo replay: stderr"; }
for want in 'package crate-A: bare model' 'package crate-A-on-frame: frame model' \
    '20001 read, 20001 accepted, 0 rejected' 'first uplift' 'impacts' 'peak |theta|' \
    'tipped (alpha)' 'minimum margin' 'outcome'; do
    grep -qF "$want" "$TMP/out" || { show; fail "summary lacks '$want'"; }
done
echo "ok"
