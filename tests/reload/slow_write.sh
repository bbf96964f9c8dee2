#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A SIGHUP while a scene file is being rewritten never applies the file
# half-written.  The monitor (on memq://: no network needed) watches two
# crates; then
#   - a writer rewrites a.ini in place slowly: the first lines alone make a
#     valid scene of another package (no name: it would be called 'a'), and
#     the SIGHUP comes right after them; the name follows 0.6 s later.  The
#     monitor must apply the whole file (crate-Z), never the half one, and
#     say it was rewritten in place;
#   - a new file renamed over a.ini (the rename(2) convention) is applied;
#   - a file that keeps changing for longer than the monitor waits is not
#     applied at all, and the monitor goes on.
# usage: slow_write.sh SWAYWATCH
set -eu
SW=$1
"$SW" --help | grep -q '^  monitor' || { echo "no monitor in this build: skipped"; exit 77; }
T=$(mktemp -d)
M=""
cleanup() {
    [ -n "$M" ] && kill "$M" 2>/dev/null || true
    rm -rf "$T"
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*" >&2
    sed 's/^/  | /' "$T/m.err" >&2
    exit 1
}
# wait_for TEXT SECONDS: TEXT (a grep pattern) appears in the monitor's stderr
wait_for() {
    i=0
    until grep -q "$1" "$T/m.err"; do
        i=$((i + 1))
        [ "$i" -lt $(($2 * 20)) ] || fail "no '$1' after $2 s"
        sleep 0.05
    done
}

printf '[package]\nname = crate-A\nheight = 2.0\nwidth = 0.728\nmass = 1000\n' >"$T/a.ini"
printf '[package]\nname = crate-B\nheight = 2.0\nwidth = 0.728\nmass = 1000\n' >"$T/b.ini"
"$SW" monitor -l memq:// --scene "$T/a.ini" --scene "$T/b.ini" 2>"$T/m.err" &
M=$!
sleep 1
kill -0 "$M" 2>/dev/null || fail "the monitor did not start"

# 1. In place, slowly; SIGHUP mid-write.
python3 - "$T/a.ini" "$T/half" <<'PY' &
import os, sys, time
with open(sys.argv[1], "w") as f:  # truncated: the same inode, rewritten
    f.write("[package]\nheight = 2.0\nwidth = 0.6\nmass = 1000\n")
    f.flush()
    open(sys.argv[2], "w").close()  # the first lines are there
    time.sleep(0.6)
    f.write("name = crate-Z\n")
PY
W=$!
until [ -e "$T/half" ]; do sleep 0.01; done
kill -HUP "$M"
wait "$W"
wait_for 'reload: .* rebuilt, the others kept' 10
grep -q "reload: crate-Z rebuilt from $T/a.ini (scene changed; it was rewritten in place" \
    "$T/m.err" || fail "the whole rewritten file was not applied"
if grep -q 'reload: a rebuilt' "$T/m.err"; then fail "the half-written file was applied"; fi
grep -q 'reload: 1 of 2 packages rebuilt' "$T/m.err" || fail "crate-B was rebuilt too"

# 2. The rename(2) convention.
printf '[package]\nname = crate-Y\nheight = 2.0\nwidth = 0.7\nmass = 1000\n' >"$T/a.ini.new"
mv "$T/a.ini.new" "$T/a.ini"
kill -HUP "$M"
wait_for 'reload: crate-Y rebuilt' 10
if grep 'reload: crate-Y rebuilt' "$T/m.err" | grep -q 'in place'; then
    fail "a renamed file was called rewritten in place"
fi

# 3. A file that never stops changing (a valid scene of crate-W, rewritten
# every 0.3 s) is not applied; the monitor goes on.
python3 - "$T/a.ini" "$T/stop" <<'PY' &
import os, sys, time
k = 0
while not os.path.exists(sys.argv[2]) and k < 200:
    with open(sys.argv[1], "w") as f:
        f.write("[package]\nname = crate-W\nheight = 2.0\nwidth = 0.7\nmass = 1000\n# %d\n" % k)
    k += 1
    time.sleep(0.3)
PY
W=$!
sleep 0.5
kill -HUP "$M"
wait_for 'is still changing .* s after the SIGHUP: scene files not applied' 15
touch "$T/stop"
wait "$W"
if grep -q 'reload: crate-W rebuilt' "$T/m.err"; then fail "a file still changing was applied"; fi
kill -0 "$M" 2>/dev/null || fail "the monitor died"
kill -TERM "$M"
rc=0
wait "$M" || rc=$?
M=""
[ "$rc" -eq 0 ] || fail "monitor exit $rc"
echo "ok"
