# SPDX-License-Identifier: GPL-3.0-or-later
# fixtures.sh - one fixture per real-world shape of a logger export, made
# from the sample drive: each replayed with no options gives the clean
# log's verdict or is refused with the reason (never another verdict with
# exit 0), and with the right options gives the clean verdict.  The clean
# verdict is the sample log's own, replayed here.
. "$(dirname "$0")/lib.sh"
LOGS=$SRC/sample_logs
SCENES="--scene $LOGS/crate.ini --scene $LOGS/crate-on-frame.ini"

# verdict JSON: "bare-overturned frame-overturned frame-overturn-time"
verdict() {
    python3 - "$1" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
p = j["packages"]
t = p[1]["overturn_time"]
print(p[0]["overturned"], p[1]["overturned"], "%.3f" % t if t is not None else "none")
PY
}

# replay FILE OPTIONS...: $RC, $TMP/out (JSON), $TMP/err
replay() {
    f=$1
    shift
    # shellcheck disable=SC2086
    run "$SW" replay "$f" $SCENES --json "$@"
}

replay "$LOGS/braking-pothole.csv"
expect_rc 0 "the clean log"
CLEAN=$(verdict "$TMP/out")
[ "$CLEAN" = "False True 8.281" ] || fail "clean verdict: $CLEAN"

# same_verdict WHAT: exit 0 and the clean verdict
same_verdict() {
    expect_rc 0 "$1"
    v=$(verdict "$TMP/out")
    [ "$v" = "$CLEAN" ] || { show; fail "$1: verdict $v, the clean log's is $CLEAN"; }
}

python3 - "$LOGS/braking-pothole.csv" "$TMP" <<'PY'
import math, random, sys
src, out = sys.argv[1], sys.argv[2]
rows = [l.strip().split(",") for l in open(src)][1:]
t = [float(r[0]) for r in rows]
a = [float(r[1]) for r in rows]
g = 9.80665
rnd = random.Random(7)
def w(name, text, mode="w", enc="utf-8", newline="\n"):
    with open(out + "/" + name, mode, encoding=enc, newline=newline) as f:
        f.write(text)
# 1. a 3-axis shock logger: BOM, CRLF, quoted header, a sample index first
lines = ['"Sample","Time (ms)","X (g)","Y (g)","Z (g)","Temp (C)"']
for i in range(len(t)):
    lines.append('%d,%.6f,%.12g,%.5f,%.5f,21.5' % (i + 1, t[i] * 1000, a[i] / g,
                                                   rnd.gauss(0, 0.01), 1 + rnd.gauss(0, 0.01)))
w("three-axis.csv", "\ufeff" + "\r\n".join(lines) + "\r\n")
# 3. a CAN-bus export: a date-time, elapsed seconds, one acceleration in G,
# about 12 Hz with irregular spacing (the value at each instant, sampled)
lines = ["Timestamp,Time (s),Acceleration Gs"]
k, tt = 0, 0.0
while tt <= t[-1]:
    i = min(int(round(tt * 1000)), len(t) - 1)
    whole = int(tt)
    lines.append("2024-05-20T12:00:%02d.%03dZ,%.3f,%.9g" % (whole, round((tt - whole) * 1000) % 1000, tt,
                                                          a[i] / g) if whole < 60 else "")
    tt += 1 / 12 + rnd.uniform(-0.02, 0.02)
w("can-bus.csv", "\n".join(l for l in lines if l) + "\n")
# 4. a phone export: unit-suffixed names, three axes, gravity on z
lines = ["time_s,ax_mps2,ay_mps2,az_mps2"]
for i in range(len(t)):
    lines.append("%.3f,%.9g,%.4f,%.4f" % (t[i], a[i], rnd.gauss(0, 0.05), g + rnd.gauss(0, 0.05)))
w("phone.csv", "\n".join(lines) + "\n")
# 5. decimal commas in a ';' export
lines = ["time_s;accel_mps2"] + ["%s;%s" % (("%.3f" % t[i]).replace(".", ","),
                                            ("%.9g" % a[i]).replace(".", ",")) for i in range(len(t))]
w("decimal-comma.csv", "\n".join(lines) + "\n")
# 6. swapped columns, no header
w("swapped.csv", "\n".join("%.9g,%.3f" % (a[i], t[i]) for i in range(len(t))) + "\n")
# 7. a 2 s hole over the braking (6.5 s to 8.5 s)
lines = ["t_s,accel_mps2"] + ["%.3f,%.9g" % (t[i], a[i]) for i in range(len(t))
                              if not 6.5 < t[i] < 8.5]
w("hole.csv", "\n".join(lines) + "\n")
# 8. a 10 ms glitch of -900 m/s^2 at 4 s
lines = ["t_s,accel_mps2"] + ["%.3f,%.9g" % (t[i], -900.0 if 4.0 <= t[i] < 4.01 else a[i])
                              for i in range(len(t))]
w("glitch.csv", "\n".join(lines) + "\n")
# 9. a vertical accelerometer column that reads +1 g at rest
lines = ["t_s,accel_mps2,z_mps2"] + ["%.3f,%.9g,%.5f" % (t[i], a[i], g + rnd.gauss(0, 0.02))
                                     for i in range(len(t))]
w("vertical.csv", "\n".join(lines) + "\n")
PY

# 1. read by its names: time in ms, x in g
replay "$TMP/three-axis.csv"
same_verdict "3-axis export"
expect_err 'time: column 2 "Time (ms)", ms (from the header); accel: column 3 "X (g)", g (from the header)' \
    "3-axis export: the columns said"

# 2. time_ms;accel_g, the project's own export
replay "$LOGS/braking-pothole-g-ms.csv"
same_verdict "time_ms;accel_g"

# 3. CAN-bus at 12 Hz: elapsed seconds chosen over the date-time; a warning
# that short shocks are not resolved; the braking's verdict survives
replay "$TMP/can-bus.csv"
expect_rc 0 "CAN-bus export"
expect_err 'time: column 2 "Time (s)", s (from the header); accel: column 3 "Acceleration Gs", g' \
    "CAN-bus: the columns said"
expect_err "shocks shorter than a few sample intervals" "CAN-bus: the low rate said"
json_check "$TMP/out" 'j["packages"][1]["overturned"] and abs(j["input"]["rate"] - 12) < 2'
json_check "$TMP/out" 'j["input"]["check"] is not None and not j["input"]["forced"]'

# 4. a phone: x is the longitudinal axis; z (with gravity) not used
replay "$TMP/phone.csv"
same_verdict "phone export"

# 5. decimal commas, detected
replay "$TMP/decimal-comma.csv"
same_verdict "decimal comma"
replay "$TMP/decimal-comma.csv" --decimal-comma
same_verdict "decimal comma, said"

# 6. swapped columns, no header: refused (the times do not increase)
replay "$TMP/swapped.csv"
expect_rc 2 "swapped columns"
expect_err "no verdict" "swapped columns: refused"
replay "$TMP/swapped.csv" --time-col 2 --accel-col 1
same_verdict "swapped columns, said"

# 7. a hole over the braking: counted, and the verdict marked incomplete
replay "$TMP/hole.csv"
expect_rc 0 "a hole"
json_check "$TMP/out" 'j["input"]["gaps"] == 1 and j["input"]["incomplete"] is True'
json_check "$TMP/out" 'abs(j["input"]["gap_max"] - 2.0) < 1e-6'
grep -q "note: a gap of 2 s" "$TMP/err" || { show; fail "a hole: not said"; }
run "$SW" replay "$TMP/hole.csv" $SCENES
grep -q "VERDICT INCOMPLETE" "$TMP/out" || { show; fail "a hole: the summary does not say incomplete"; }

# 8. a glitch: the spike refused (its ten rows named), the verdict clean
replay "$TMP/glitch.csv"
same_verdict "a glitch"
[ "$(grep -c '(implausible)' "$TMP/err")" -eq 10 ] || { show; fail "a glitch: 10 rows refused"; }

# 9. a vertical column with gravity: refused until said; then clean
replay "$TMP/vertical.csv" --vert-col z_mps2
expect_rc 2 "vertical with gravity"
expect_err "it includes gravity" "vertical with gravity: refused"
replay "$TMP/vertical.csv" --vert-col z_mps2 --vert-includes-gravity
same_verdict "vertical with gravity, said"

# An option always wins over the header, and a contradiction is said.
replay "$LOGS/braking-pothole-g-ms.csv" --accel-unit m/s2 --force
expect_err '--accel-unit m/s^2 contradicts the header'"'"'s "accel_g" (g); using m/s^2 as given' \
    "a unit against the header"
# The same export with its ms read as seconds: 1 Hz, no verdict.
replay "$LOGS/braking-pothole-g-ms.csv" --time-unit s
expect_rc 2 "ms read as seconds"
expect_err "no vehicle log is that slow; a time column in ms or us read as seconds?" \
    "ms read as seconds: the reason"
# Date-times: timed from the log's start, the absolute start said once.
replay "$TMP/can-bus.csv" --time-col Timestamp
expect_rc 0 "date-time column"
json_check "$TMP/out" 'j["input"]["start_absolute"] == "2024-05-20T12:00:00.000Z" and j["input"]["start"] == 0'
json_check "$TMP/out" 'j["packages"][1]["overturned"] and j["packages"][1]["overturn_time"] < 60'
