#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Install what is missing, build, and replay the sample drive for the crate
# standing free and for the same crate on a support frame.
#   scripts/demo.sh            (BUILD=dir to build elsewhere; default build/)
set -eu
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
BUILD=${BUILD:-build}
cmake -S . -B "$BUILD" >/dev/null
cmake --build "$BUILD" -j "$(nproc)" >/dev/null
set -- replay sample_logs/braking-pothole.csv \
    --scene sample_logs/crate.ini --scene sample_logs/crate-on-frame.ini
echo "\$ swaywatch $*"
echo
"$BUILD"/swaywatch "$@"
