#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Build the libFuzzer targets of tests/fuzz with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and run each one in turn for SECONDS (default
# 60), starting from the seed corpus in tests/fuzz/corpus/<target>/.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#
# Prints one line per target on standard output, for the CI log:
#   fuzz csv: 81234 inputs in 60 s (1353/s; 1420 per s of CPU, 57.2 s), corpus 212, load 1.20
# (the inputs run, their rate per second of wall time, their rate per
# second of CPU the fuzzer used, its children included, and that CPU time,
# the corpus at the end, the machine's load average when the target
# ended).  On a loaded machine the wall rate falls and the CPU rate holds:
# a wall rate far below the CPU rate is the machine, not the target.  Fails on a
# crash, a leak, a sanitizer report or a timeout.  The input that did it is
# left in $FUZZ_BUILD/artifacts/<target>/; after fixing the bug, keep it as
# a regression test in tests/fuzz/regressions/<target>/ (the normal build
# replays that folder).  New inputs the fuzzer finds go to
# $FUZZ_BUILD/corpus/<target>/, never into the source tree.
#
# Targets run one after the other (CI machines have 2 cores, and the time
# budget is total).  FUZZ_BUILD defaults to build-fuzz.  Each target should
# run at least 1000 inputs per second here, gnuplot included (its runs of
# gnuplot, one input in 64 at some 20 ms of CPU each, are a third of its
# time and count in its CPU: it runs about 1,400 a second of CPU); one that
# runs fewer is named on standard error with both rates, not failed: a
# loaded machine is not a bug.
set -eu
cd "$(dirname "$0")/.."
SECS=${1:-60}
[ $# -gt 0 ] && shift
B=${FUZZ_BUILD:-build-fuzz}
JOBS=${JOBS:-2}

if ! command -v clang >/dev/null 2>&1; then
    echo "swaywatch fuzz: clang not found (scripts/setup-debian.sh installs it)" >&2
    exit 1
fi
cmake -S . -B "$B" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSW_FUZZ=ON -DSW_SANITIZE=ON -DSW_WERROR=ON >/dev/null
TARGETS=${*:-csv timecol scene gnuplot accel feed lcmlog}
# Targets that need optional dependencies (accel, feed, lcmlog: LCM) exist only when those
# were found.
BUILT=""
for t in $TARGETS; do
    cmake --build "$B" --target help 2>/dev/null | grep " fuzz_$t\$" >/dev/null && BUILT="$BUILT $t"
done
# shellcheck disable=SC2086
if ! cmake --build "$B" -j "$JOBS" $(for t in $BUILT; do printf ' --target fuzz_%s' "$t"; done) \
    >"$B/build.log" 2>&1; then
    tail -40 "$B/build.log" >&2
    exit 1
fi

# Leaks are findings too; a wrong result aborts, and abort is a crash.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# CPU seconds (user + system) a fuzzer used, its children (gnuplot)
# included: the difference of this shell's children's times (`times`,
# second line) written into FILE0 before its run and FILE1 after (by the
# shell itself: a subshell's `times` starts from zero).
cpu_used() {
    awk 'FNR == 2 { n = 0; for (i = 1; i <= 2; i++) { split($i, a, "m"); sub("s", "", a[2]);
                    n += a[1] * 60 + a[2] } c[FILENAME == f0] = n }
         END { printf "%.1f", c[0] - c[1] }' f0="$1" "$1" "$2"
}

# report TARGET LOG CPU: "fuzz TARGET: N inputs in S s (R/s; C per s of
# CPU, CPU s), corpus C, load L" from libFuzzer's log and the CPU seconds.
report() {
    name=$1 log=$2 cpu=$3
    n=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
    corpus=$(sed -n 's/.* corp: \([0-9]*\)\/.*/\1/p' "$log" | tail -1)
    load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo '?')
    # the seconds it ran: fewer than asked when it stopped on a finding
    secs=$SECS
    [ "${rate:-0}" -gt 0 ] && [ $((${n:-0} / rate)) -lt "$SECS" ] && secs=$((${n:-0} / rate))
    crate=$(awk -v n="${n:-0}" -v c="$cpu" 'BEGIN { printf "%d", (c > 0 ? n / c : 0) }')
    echo "fuzz $name: ${n:-0} inputs in $secs s (${rate:-0}/s; $crate per s of CPU, $cpu s)," \
        "corpus ${corpus:-0}, load $load"
    if [ "${rate:-0}" -lt 1000 ]; then
        echo "swaywatch fuzz: $name ran ${rate:-0} inputs/s, fewer than 1000" \
            "($crate per s of CPU, load $load)" >&2
    fi
}

status=0
for t in $BUILT; do
    work="$B/corpus/$t"
    art="$B/artifacts/$t"
    mkdir -p "$work" "$art"
    dict=""
    [ -f "tests/fuzz/$t.dict" ] && dict="-dict=tests/fuzz/$t.dict"
    # the longest input that means something to the target
    case $t in
        gnuplot) maxlen=1024 ;;
        timecol) maxlen=4098 ;;
        lcmlog) maxlen=16385 ;;
        *) maxlen=65536 ;;
    esac
    echo "swaywatch fuzz: $t for $SECS s" >&2
    times >"$B/times.0"
    # The first folder receives new inputs; the seed corpus is only read.
    # shellcheck disable=SC2086
    if ! "$B/tests/fuzz/fuzz_$t" -max_total_time="$SECS" -timeout=20 -rss_limit_mb=2048 \
        -max_len="$maxlen" -print_final_stats=1 -artifact_prefix="$art/" $dict \
        "$work" "tests/fuzz/corpus/$t" >"$B/fuzz-$t.log" 2>&1; then
        times >"$B/times.1"
        cpu=$(cpu_used "$B/times.0" "$B/times.1")
        tail -60 "$B/fuzz-$t.log" >&2
        report "$t" "$B/fuzz-$t.log" "$cpu"
        echo "swaywatch fuzz: $t FAILED; input kept in $art/" >&2
        status=1
    else
        times >"$B/times.1"
        cpu=$(cpu_used "$B/times.0" "$B/times.1")
        report "$t" "$B/fuzz-$t.log" "$cpu"
    fi
done
exit $status
