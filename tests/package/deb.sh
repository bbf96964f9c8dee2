#!/bin/sh
# The Debian packages: cpack builds them from the build folder; apt-get
# installs them (offline: every dependency is already on a build machine);
# the installed command runs, a program builds against the installed
# library through pkg-config and runs; the packages are purged again, so
# the machine is left as it was.  Needs root: exits 77 (skipped) otherwise.
# usage: deb.sh BUILD_DIR SOURCE_DIR   (env: SW_VERSION, SW_LCM, SW_MAN, SW_CC_FLAGS)
set -eu
BUILD=$1 SRC=$2
if [ "$(id -u)" -ne 0 ]; then
    echo "deb.sh: not root: skipped (installs packages)"
    exit 77
fi
fail() { echo "deb.sh: $*" >&2; exit 1; }
PKGS="swaywatch libswaywatch-dev"
# Left behind only by a run of this test that was killed before its cleanup.
MARK=/var/lib/swaywatch-package-test
APT="apt-get -q -y -o DPkg::Lock::Timeout=300"
T=$(mktemp -d)
installed=0
cleanup() {
    if [ "$installed" = 1 ]; then
        $APT purge $PKGS >"$T/purge.log" 2>&1 || cat "$T/purge.log" >&2
        rm -f "$MARK"
    fi
    rm -rf "$T"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

# One run at a time on this machine (other build folders run this test too).
exec 9>/var/lock/swaywatch-package-test.lock
flock -w 600 9 || fail "another package test holds the lock"

for p in $PKGS; do
    if dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q ' installed$'; then
        [ -e "$MARK" ] || fail "$p is installed on this machine: the test would replace and remove it; remove it first (apt-get purge $PKGS)"
        echo "deb.sh: purging $p left by an interrupted run"
        $APT purge $PKGS >/dev/null
        rm -f "$MARK"
    fi
done

cpack -G DEB -B "$T/pkg" --config "$BUILD/CPackConfig.cmake" >"$T/cpack.log" 2>&1 ||
    { cat "$T/cpack.log" >&2; fail "cpack failed"; }
main=$(ls "$T"/pkg/swaywatch_"$SW_VERSION"-*.deb 2>/dev/null | head -n 1)
dev=$(ls "$T"/pkg/libswaywatch-dev_"$SW_VERSION"-*.deb 2>/dev/null | head -n 1)
[ -n "$main" ] && [ -n "$dev" ] || { ls -l "$T/pkg" >&2; fail "packages not made"; }

# Control fields: run-time dependencies found by dpkg-shlibdeps.
depends=$(dpkg-deb -f "$main" Depends)
echo "deb.sh: $(basename "$main"): Depends: $depends"
for d in libc6 libgsl27 libcsv3 libinih1; do
    echo "$depends" | grep -q "\b$d\b" || fail "swaywatch does not depend on $d"
done
if [ "${SW_LCM:-0}" = 1 ]; then
    echo "$depends" | grep -q '\bliblcm1\b' || fail "swaywatch does not depend on liblcm1"
fi
[ -n "$(dpkg-deb -f "$main" Maintainer)" ] || fail "no Maintainer"
dpkg-deb -f "$main" Description | grep -q 'floating cargo' || fail "no Description"
dpkg-deb -f "$dev" Depends | grep -q "swaywatch (= $SW_VERSION-" || fail "-dev does not depend on swaywatch"
dpkg-deb -c "$main" | grep ' ./usr/bin/swaywatch$' >/dev/null || fail "no /usr/bin/swaywatch in the package"
dpkg-deb -c "$dev" | grep '/pkgconfig/swaywatch.pc$' >/dev/null || fail "no swaywatch.pc in the -dev package"

touch "$MARK"
installed=1
$APT install --no-install-recommends "$main" "$dev" >"$T/apt.log" 2>&1 ||
    { cat "$T/apt.log" >&2; fail "apt-get install failed"; }
dpkg -s swaywatch | grep -q '^Status: install ok installed' || fail "swaywatch not installed"

# The installed command (by full path: a build folder may come first in PATH).
[ "$(/usr/bin/swaywatch --version)" = "swaywatch $SW_VERSION" ] || fail "swaywatch --version"
/usr/bin/swaywatch replay --version | grep -qx "swaywatch replay $SW_VERSION" ||
    fail "swaywatch replay --version"
/usr/bin/swaywatch --help >/dev/null
[ -e /usr/lib/systemd/system/swaywatch-monitor.service ] || fail "no systemd unit"
[ -e /usr/share/bash-completion/completions/swaywatch ] || fail "no bash completion"
if [ "${SW_MAN:-0}" = 1 ]; then
    [ -e /usr/share/man/man1/swaywatch-replay.1 ] || fail "no manual page of replay"
fi
if [ "${SW_LCM:-0}" = 1 ]; then
    [ -e /usr/share/swaywatch/lcmtypes/state_t.lcm ] || fail "no LCM definitions"
fi

# A program against the installed library, through pkg-config only.
cd "$T"
cc ${SW_CC_FLAGS:-} -o tipcheck "$SRC/docs/examples/tipcheck.c" $(pkg-config --cflags --libs swaywatch)
ldd ./tipcheck | grep -Eq 'libswaywatch\.so\.0 => (/usr)?/lib/' ||
    fail "tipcheck does not use the installed libswaywatch.so.0"
./tipcheck

$APT purge $PKGS >"$T/purge.log" 2>&1 || { cat "$T/purge.log" >&2; fail "apt-get purge failed"; }
installed=0
rm -f "$MARK"
for p in $PKGS; do
    if dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q ' installed$'; then
        fail "$p still installed"
    fi
done
[ ! -e /usr/bin/swaywatch ] || fail "/usr/bin/swaywatch left behind"
echo "deb.sh: ok"
