#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Install the Debian 12 packages swaywatch needs to build, test and plot,
# skipping those already present.  chromium renders forensics' HTML report
# in its test (tests/cli/report.sh).  Needs root (or sudo) only when something
# is missing.
set -eu
PKGS="build-essential cmake pkg-config liblcm-dev liblcm-bin libcsv-dev libgsl-dev
libcmocka-dev libinih-dev libsodium-dev libjansson-dev libglib2.0-dev gnuplot-nox python3
iproute2 util-linux clang clang-format libclang-rt-14-dev valgrind help2man liblcm-java
dpkg-dev file lintian libsystemd-dev libncurses-dev tmux openmpi-bin libopenmpi-dev
chromium"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
        missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "swaywatch setup: installing$missing" >&2
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
