#!/bin/sh
# Set up (Debian packages), build with warnings as errors, run the whole test
# suite.  Used by .ci/run and by README's Quick start.
set -eu
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
BUILD=${BUILD:-build}
cmake -S . -B "$BUILD" -DSW_WERROR=ON >/dev/null
cmake --build "$BUILD" -j "$(nproc)"
ctest --test-dir "$BUILD" --output-on-failure -j "$(nproc)"
