#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# 'sudo cmake --install build' as the README does it, to /usr/local: a
# program linked to the installed libswaywatch.so.0 runs at once, without
# LD_LIBRARY_PATH (the install ran ldconfig), and no longer finds it after
# the uninstall target (which ran ldconfig again).  In a private mount
# namespace, with an empty /usr/local and a private copy of /etc (the
# linker's cache), so the machine is not touched.  Needs root and a build
# configured for /usr/local: exits 77 (skipped) otherwise.
# usage: ldconfig.sh BUILD_DIR SOURCE_DIR   (env: SW_CC_FLAGS)
set -eu
BUILD=$(cd "$1" && pwd) SRC=$(cd "$2" && pwd)
fail() { echo "ldconfig.sh: $*" >&2; exit 1; }
if [ -z "${SW_IN_MOUNTNS:-}" ]; then
    if [ "$(id -u)" -ne 0 ]; then
        echo "ldconfig.sh: not root: skipped (installs to /usr/local in a mount namespace)"
        exit 77
    fi
    prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$BUILD/CMakeCache.txt")
    if [ "$prefix" != /usr/local ]; then
        echo "ldconfig.sh: the build's prefix is $prefix, not /usr/local: skipped"
        exit 77
    fi
    if ! unshare -m true 2>/dev/null; then
        echo "ldconfig.sh: cannot make a mount namespace: skipped"
        exit 77
    fi
    SW_IN_MOUNTNS=1 exec unshare -m sh "$0" "$@"
fi

T=$(mktemp -d)
M=$BUILD/install_manifest.txt
if [ -e "$M" ]; then cp -p "$M" "$T/manifest.saved"; fi
restore() {
    if [ -e "$T/manifest.saved" ]; then cp -p "$T/manifest.saved" "$M"; else rm -f "$M"; fi
    rm -rf "$T"
}
trap restore EXIT

mount --make-rprivate /
mount -t tmpfs tmpfs /usr/local
mkdir "$T/etc"
cp -a /etc/. "$T/etc/"
mount --bind "$T/etc" /etc

cmake --install "$BUILD" >"$T/install.log"
grep -q 'Running: ldconfig (/usr/local/lib' "$T/install.log" ||
    { cat "$T/install.log" >&2; fail "the install did not run ldconfig"; }
ldconfig -p | grep -q 'libswaywatch.so.0 .*=> /usr/local/lib/libswaywatch.so.0$' ||
    fail "libswaywatch.so.0 is not in the linker's cache after the install"

export PKG_CONFIG_PATH=/usr/local/lib/pkgconfig
cc ${SW_CC_FLAGS:-} -o "$T/tipcheck" "$SRC/docs/examples/tipcheck.c" $(pkg-config --cflags --libs swaywatch)
unset LD_LIBRARY_PATH
"$T/tipcheck" >"$T/run.log" 2>&1 || { cat "$T/run.log" >&2; fail "tipcheck does not run after the install"; }
ldd "$T/tipcheck" | grep -q 'libswaywatch.so.0 => /usr/local/lib/libswaywatch.so.0' ||
    fail "tipcheck does not use /usr/local/lib/libswaywatch.so.0"

cmake --build "$BUILD" --target uninstall >"$T/uninstall.log" 2>&1 ||
    { cat "$T/uninstall.log" >&2; fail "the uninstall target failed"; }
left=$(find /usr/local ! -type d | head -n 5)
[ -z "$left" ] || fail "left after uninstall: $left"
if ldconfig -p | grep -q libswaywatch; then fail "libswaywatch still in the linker's cache"; fi
if "$T/tipcheck" >/dev/null 2>&1; then fail "tipcheck still runs after the uninstall"; fi
echo "ldconfig.sh: ok (installed, ran without LD_LIBRARY_PATH, uninstalled)"
