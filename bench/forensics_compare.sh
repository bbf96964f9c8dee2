#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# forensics_compare.sh - evidence that a change to the safety-factor search
# keeps every answer: the forensics JSON and text of two builds, compared
# without what names the build or the command line, on
#   - the hour-long drive of bench/drive_log.py, the crate with a frame
#     (5.59 rad/s) and a cushion (30 rad/s) what-if;
#   - every sample log (sample_logs/*.csv; braking-pothole-g-ms.csv read
#     with the options its README gives) with every sample scene: the
#     catalogue of supports, and for the bare crate also the frame and
#     cushion what-ifs above and a --size what-if.
# Exit 0 when every case agrees, 1 with the differences.  QUICK=1 leaves
# out the hour-long drive (a minute or two per build).
#   bench/forensics_compare.sh BEFORE_BUILD AFTER_BUILD
set -eu
A=$(cd "${1:?usage: forensics_compare.sh BEFORE_BUILD AFTER_BUILD}" && pwd)
B=$(cd "${2:?usage: forensics_compare.sh BEFORE_BUILD AFTER_BUILD}" && pwd)
SRC=$(cd "$(dirname "$0")/.." && pwd)
TMP=$(mktemp -d /tmp/sw-forensics-compare.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
S=$SRC/sample_logs
cp "$S"/*.csv "$S"/*.ini "$TMP/"

# cases: NAME|LOG|ARGS (LOG and scenes in the temporary folder, by name)
WHATIF="--frame-omega 5.59 --cushion-omega 30"
{
    if [ -z "${QUICK:-}" ]; then
        python3 "$SRC/bench/drive_log.py" >"$TMP/drive.csv"
        echo "drive|drive.csv|--scene crate.ini $WHATIF"
    fi
    for log in "$S"/*.csv; do
        log=$(basename "$log")
        opts=
        case $log in
            braking-pothole-g-ms.csv) opts="--delimiter ; --time-unit ms --accel-unit g" ;;
        esac
        for sc in crate crate-on-frame crate-on-cushion; do
            echo "${log%.csv}-$sc|$log|--scene $sc.ini $opts"
        done
        echo "${log%.csv}-crate-whatif|$log|--scene crate.ini $opts $WHATIF --size 1.6x0.728"
    done
} >"$TMP/cases"

# strip FILE: the JSON without what names the build or the command
strip() {
    python3 - "$1" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
for k in ("command", "command_line", "build"):
    j.pop(k, None)
print(json.dumps(j, indent=1, sort_keys=True))
PY
}

bad=0
while IFS='|' read -r name log args; do
    for side in A B; do
        eval "build=\$$side"
        # shellcheck disable=SC2086
        (cd "$TMP" && "$build/swaywatch" forensics "$log" $args --json >"$TMP/$name.$side.json" \
            2>"$TMP/$name.$side.err") || true
        # shellcheck disable=SC2086
        (cd "$TMP" && "$build/swaywatch" forensics "$log" $args 2>/dev/null |
            grep -v '^  program \|^  command ' >"$TMP/$name.$side.txt") || true
        strip "$TMP/$name.$side.json" >"$TMP/$name.$side.sjson" 2>>"$TMP/$name.$side.err" ||
            echo "(no JSON)" >"$TMP/$name.$side.sjson"
    done
    no=
    for side in A B; do
        grep -q '"safety_factor"' "$TMP/$name.$side.sjson" || no="$no $side"
    done
    if [ -n "$no" ]; then
        echo "$name: NO ANSWER from$no"
        for side in $no; do head -5 "$TMP/$name.$side.err"; done
        bad=1
    elif cmp -s "$TMP/$name.A.sjson" "$TMP/$name.B.sjson" &&
        cmp -s "$TMP/$name.A.txt" "$TMP/$name.B.txt"; then
        echo "$name: the same"
    else
        echo "$name: DIFFERENT"
        diff "$TMP/$name.A.sjson" "$TMP/$name.B.sjson" || true
        diff "$TMP/$name.A.txt" "$TMP/$name.B.txt" || true
        bad=1
    fi
done <"$TMP/cases"
exit $bad
