# SPDX-License-Identifier: GPL-3.0-or-later
# elcentro.sh - a third-party record: the 1940 El Centro NS accelerogram
# (PEER AT2 format: 4 header lines, then 8 values per line in g, dt 0.02 s),
# converted to CSV here and replayed in g; every sample must be accounted for.
. "$(dirname "$0")/lib.sh"
AT2=$SRC/tests/data/elcentro-1940-ns.AT2 # provenance: tests/data/README.md
[ -r "$AT2" ] || fail "$AT2 not found"

# Fixed-width 8F10.5: cut by columns, not by blanks, so touching negative
# numbers are still split correctly.
awk 'NR == 4 { if ($0 !~ /NPTS= *1559/) exit 1 }
     NR > 4 {
        for (i = 0; i < 8; i++) {
            f = substr($0, 1 + 10 * i, 10)
            if (f ~ /[0-9]/) { gsub(/ /, "", f); printf "%.2f,%s\n", n * 0.02, f; n++ }
        }
     }
     BEGIN { print "t_s,accel_g" }
     END { if (n != 1559) { print "converted " n " values" > "/dev/stderr"; exit 1 } }' "$AT2" >"$TMP/elcentro.csv" ||
    fail "conversion of $AT2"
[ "$(wc -l <"$TMP/elcentro.csv")" -eq 1560 ] || fail "converted CSV should have 1559 rows + header"

run "$SW" replay "$TMP/elcentro.csv" --accel-unit g --scene "$SRC/sample_logs/crate.ini" --json
expect_rc 0 "El Centro replay"
json_check "$TMP/out" 'j["samples_read"] == 1559 and j["samples_rejected"] == 0'
json_check "$TMP/out" 'j["packages"][0]["samples_read"] == 1559 and j["packages"][0]["samples_rejected"] == 0'
# Peak 0.319 g = 3.13 m/s^2 is below the crate's uplift threshold
# g tan(alpha) = 9.81 * 0.364 = 3.57 m/s^2: it never leaves the upright position.
json_check "$TMP/out" 'j["packages"][0]["uplift_time"] is None and j["packages"][0]["impacts"] == 0 and not j["packages"][0]["overturned"]'
# A narrower crate (alpha = atan(0.2/1.0), threshold 1.96 m/s^2) does rock.
run "$SW" replay "$TMP/elcentro.csv" --accel-unit g --scene "$SRC/sample_logs/crate.ini" \
    --set package.width=0.4 --json
expect_rc 0 "El Centro replay, narrow crate"
json_check "$TMP/out" 'j["packages"][0]["uplift_time"] is not None'
echo "ok"
