#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Set up (Debian packages), build with warnings as errors and run the whole
# test suite; compile the tree with clang too; then build and run the suite
# a second time under AddressSanitizer and UndefinedBehaviorSanitizer
# (separate build folder), and run each fuzz target briefly.  Used by .ci/run and by README's Quick start.
#
#   SW_QUICK=1       only the first pass (a quick local check)
#   FUZZ_SECONDS=N   seconds per fuzz target (default 60; 0: no fuzzing)
#   BUILD, CLANG_BUILD, ASAN_BUILD, FUZZ_BUILD   build folders (build,
#                    build-clang, build-asan, build-fuzz)
set -eu
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
# The tree's conventions first, in seconds: the style of .clang-format
# and the licence line on every source file.
scripts/format.sh --check
scripts/spdx.sh --check
JOBS=$(nproc)
START=$(date +%s)
elapsed() {
    echo "swaywatch tests: $1 done after $(($(date +%s) - START)) s" >&2
}

BUILD=${BUILD:-build}
# With MPI (Open MPI, from the setup): the batch and boundary tests under
# mpirun run only in such a build.
cmake -S . -B "$BUILD" -DSW_WERROR=ON -DSW_MPI=ON >/dev/null
cmake --build "$BUILD" -j "$JOBS"
ctest --test-dir "$BUILD" --output-on-failure -j "$JOBS"
elapsed "build and tests"
[ "${SW_QUICK:-0}" = 1 ] && exit 0

# The whole tree, tests included, compiled by clang with warnings as
# errors (compile only, about 30 s): clang warns where gcc does not (a
# positional initializer that leaves fields out, for one).
CLANG_BUILD=${CLANG_BUILD:-build-clang}
cmake -S . -B "$CLANG_BUILD" -DCMAKE_C_COMPILER=clang -DSW_WERROR=ON -DSW_MPI=OFF >/dev/null
cmake --build "$CLANG_BUILD" -j "$JOBS"
elapsed "clang build"

# The same suite with ASan + UBSan: any report aborts the test (the build
# uses -fno-sanitize-recover).  Left out: valgrind tests (they are in the
# first pass: valgrind cannot run ASan binaries), the soak test, whose long
# monitor run the first pass already watches for growth, and the packaging
# tests (a sanitized library is no package: programs built without ASan
# cannot link it, and the .deb would depend on libasan).  Built without
# MPI: Open MPI's own allocations, never freed, would fail LeakSanitizer;
# the batch's threads are checked here all the same.
ASAN_BUILD=${ASAN_BUILD:-build-asan}
cmake -S . -B "$ASAN_BUILD" -DSW_WERROR=ON -DSW_SANITIZE=ON -DSW_MPI=OFF >/dev/null
cmake --build "$ASAN_BUILD" -j "$JOBS"
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1} \
    UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    ctest --test-dir "$ASAN_BUILD" --output-on-failure -j "$JOBS" -LE 'soak|valgrind|package'
elapsed "sanitizer build and tests"

# Seven targets (csv, timecol, scene, gnuplot, accel, feed, lcmlog) one
# after the other, 60 s each: 7 min, plus the clang build of build-fuzz
# (about a minute on 2 cores).  Each prints its count of inputs and their
# rate into the log ("fuzz csv: 81234 inputs in 60 s (1353/s), ...").
# With the two passes above (about 8 min) the whole run takes about 16 min
# of CI's 90.
FUZZ_SECONDS=${FUZZ_SECONDS:-60}
if [ "$FUZZ_SECONDS" -gt 0 ]; then
    scripts/fuzz.sh "$FUZZ_SECONDS"
    elapsed "fuzzing"
fi
