#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# forensics holds the whole log in memory; from an endless pipe it used to
# grow until the memory ran out.  It now stops at --max-samples with exit
# 2 and a message naming the cap, under a memory limit too (not with the
# sanitizers, which reserve terabytes of address space).
. "$(dirname "$0")/lib.sh"

SCENE=$SRC/sample_logs/crate.ini
cat >"$TMP/endless.py" <<'PY'
import sys
print("t,a")
i = 0
try:
    while True:
        sys.stdout.write(f"{i * 0.001:.3f},0\n")
        i += 1
except BrokenPipeError:
    pass
PY
LIMIT="ulimit -v 400000;"
ldd "$SW" 2>/dev/null | grep -q 'libasan' && LIMIT=""
run timeout 60 sh -c "python3 '$TMP/endless.py' | { $LIMIT exec '$SW' forensics - --scene '$SCENE' \
    --max-samples 100000 --no-what-if -q; }"
expect_rc 2 "forensics from an endless pipe"
expect_err "(stdin): more than 100000 samples" "forensics from an endless pipe"
expect_err "is the cap (--max-samples)" "forensics from an endless pipe"

# A log within the cap is read as before; --max-samples has a floor.
run "$SW" forensics "$SRC/sample_logs/hard-stop-overturn.csv" --scene "$SCENE" \
    --max-samples 8001 --no-what-if -q
expect_rc 0 "a log of exactly --max-samples samples"
run "$SW" forensics "$SRC/sample_logs/hard-stop-overturn.csv" --scene "$SCENE" \
    --max-samples 8000 --no-what-if -q
expect_rc 2 "a log one sample over --max-samples"
expect_err "more than 8000 samples" "a log one sample over --max-samples"
echo "ok"
