#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian packages: cpack builds them from the build folder; their
# control fields and contents are checked and lintian finds no error in them
# (its warnings are the ones docs/deployment.md explains); apt-get
# installs them (offline: every dependency is already on a build machine);
# the installed command runs, a program builds against the installed
# library through pkg-config and runs; the packages are purged again, so
# the machine is left as it was.  Needs root: exits 77 (skipped) otherwise.
# The vehicle package never depends on MPI (it pulled in Open MPI, 71
# packages instead of 24, when the build found MPI); a build with MPI makes
# swaywatch-mpi as a package of its own, which does.
# usage: deb.sh BUILD_DIR SOURCE_DIR   (env: SW_VERSION, SW_LCM, SW_MAN, SW_MPI, SW_CC_FLAGS)
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

for p in swaywatch-mpi $PKGS; do
    if dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q ' installed$'; then
        [ -e "$MARK" ] || fail "$p is installed on this machine: the test would replace and remove it; remove it first (apt-get purge $p)"
        echo "deb.sh: purging $p left by an interrupted run"
        $APT purge "$p" >/dev/null
    fi
done
rm -f "$MARK"

cpack -G DEB -B "$T/pkg" --config "$BUILD/CPackConfig.cmake" >"$T/cpack.log" 2>&1 ||
    { cat "$T/cpack.log" >&2; fail "cpack failed"; }
main=$(ls "$T"/pkg/swaywatch_"$SW_VERSION"-*.deb 2>/dev/null | head -n 1)
dev=$(ls "$T"/pkg/libswaywatch-dev_"$SW_VERSION"-*.deb 2>/dev/null | head -n 1)
mpi=$(ls "$T"/pkg/swaywatch-mpi_"$SW_VERSION"-*.deb 2>/dev/null | head -n 1)
[ -n "$main" ] && [ -n "$dev" ] || { ls -l "$T/pkg" >&2; fail "packages not made"; }

# MPI only in swaywatch-mpi: the vehicle's package names no MPI library,
# its program links none.
echo "$(dpkg-deb -f "$main" Depends)" | grep -Eiq 'mpi|pmix|hwloc|fabric|ucx' &&
    fail "swaywatch depends on MPI: $(dpkg-deb -f "$main" Depends)"
dpkg-deb -x "$main" "$T/main"
if ldd "$T/main/usr/bin/swaywatch" | grep -Eiq 'libmpi|libopen-'; then
    fail "/usr/bin/swaywatch links MPI"
fi
if [ "${SW_MPI:-0}" = 1 ]; then
    [ -n "$mpi" ] || { ls -l "$T/pkg" >&2; fail "no swaywatch-mpi package in a build with MPI"; }
    dpkg-deb -f "$mpi" Depends | grep -q 'libopenmpi' ||
        fail "swaywatch-mpi does not depend on Open MPI: $(dpkg-deb -f "$mpi" Depends)"
    dpkg-deb -f "$mpi" Depends | grep -q "swaywatch (= $SW_VERSION-" ||
        fail "swaywatch-mpi does not depend on swaywatch"
    dpkg-deb -c "$mpi" | grep -q ' ./usr/bin/swaywatch-mpi$' || fail "no /usr/bin/swaywatch-mpi"
    dpkg-deb -c "$mpi" | grep -q ' ./usr/bin/swaywatch$' && fail "swaywatch-mpi has /usr/bin/swaywatch"
else
    [ -z "$mpi" ] || fail "a swaywatch-mpi package from a build without MPI"
fi

# Control fields: run-time dependencies found by dpkg-shlibdeps.
depends=$(dpkg-deb -f "$main" Depends)
echo "deb.sh: $(basename "$main"): Depends: $depends"
for d in libc6 libgsl27 libcsv3 libinih1 libsodium23 libjansson4; do
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
dpkg-deb -f "$main" Recommends | grep -q '\bbash-completion\b' || fail "swaywatch does not recommend bash-completion"
for f in Section Priority; do
    [ -n "$(dpkg-deb -f "$main" $f)" ] && [ -n "$(dpkg-deb -f "$dev" $f)" ] || fail "no $f"
done
dpkg-deb -c "$main" | grep -q ' ./usr/share/man/man5/swaywatch-scene.5.gz$' ||
    fail "no swaywatch-scene(5), compressed, in the package"
for deb in "$main" "$dev" $mpi; do
    pkg=$(dpkg-deb -f "$deb" Package)
    for f in copyright changelog.Debian.gz; do
        dpkg-deb -c "$deb" | grep -q " ./usr/share/doc/$pkg/$f\$" || fail "$pkg: no /usr/share/doc/$pkg/$f"
    done
done

# Debian's policy checker: no error; every warning it still gives is one
# that docs/deployment.md explains (by its tag).
command -v lintian >/dev/null 2>&1 ||
    fail "lintian is not installed (scripts/setup-debian.sh installs it)"
# Exit status 0: nothing at error level, 1: errors, 2: lintian itself failed.
rc=0
lintian --no-tag-display-limit "$main" "$dev" $mpi >"$T/lintian.log" 2>"$T/lintian.err" || rc=$?
grep -v '^running with root privileges' "$T/lintian.err" >&2 || true
[ "$rc" -le 1 ] || fail "lintian did not run (exit $rc)"
errors=$(grep -c '^E: ' "$T/lintian.log" || true)
warnings=$(grep -c '^W: ' "$T/lintian.log" || true)
echo "deb.sh: lintian: $errors errors, $warnings warnings"
sed 's/^/  /' "$T/lintian.log"
[ "$errors" -eq 0 ] || fail "lintian reports $errors errors"
for tag in $(sed -n 's/^W: [^:]*: \([a-z0-9.+-]*\).*/\1/p' "$T/lintian.log" | sort -u); do
    grep -Eq "\`$tag[\` ]" "$SRC/docs/deployment.md" ||
        fail "lintian warning $tag is not explained in docs/deployment.md"
done

touch "$MARK"
installed=1
[ -z "$mpi" ] || PKGS="$PKGS swaywatch-mpi"
$APT install --no-install-recommends "$main" "$dev" $mpi >"$T/apt.log" 2>&1 ||
    { cat "$T/apt.log" >&2; fail "apt-get install failed"; }
dpkg -s swaywatch | grep -q '^Status: install ok installed' || fail "swaywatch not installed"

# The installed command (by full path: a build folder may come first in PATH).
[ "$(/usr/bin/swaywatch --version | head -1)" = "swaywatch $SW_VERSION" ] ||
    fail "swaywatch --version"
/usr/bin/swaywatch --version | grep -qx 'License GPLv3+: GNU GPL version 3 or later <https://gnu.org/licenses/gpl.html>' ||
    fail "swaywatch --version: no licence"
/usr/bin/swaywatch replay --version | grep -qx "swaywatch replay $SW_VERSION" ||
    fail "swaywatch replay --version"
/usr/bin/swaywatch --help >/dev/null
U=/usr/lib/systemd/system/swaywatch-monitor.service
[ -e "$U" ] || fail "no systemd unit"
grep -q '^ExecStart=.*exec /usr/bin/swaywatch monitor ' "$U" ||
    fail "the unit does not run /usr/bin/swaywatch by full path: $(grep ExecStart "$U")"
[ -e /usr/share/bash-completion/completions/swaywatch ] || fail "no bash completion"
if [ "${SW_MAN:-0}" = 1 ]; then
    [ -e /usr/share/man/man1/swaywatch-replay.1.gz ] || fail "no manual page of replay"
fi
[ -e /usr/share/man/man5/swaywatch-scene.5.gz ] || fail "no manual page of the scene format"
# The example scenes run on the sample drive.
E=/usr/share/swaywatch/examples
/usr/bin/swaywatch replay "$E/hard-stop-overturn.csv" --scene "$E/crate.ini" \
    --scene "$E/crate-on-frame.ini" --scene "$E/crate-on-cushion.ini" >"$T/examples.txt" ||
    fail "replay of the installed example scenes"
[ "$(grep -c 'OVERTURNED' "$T/examples.txt")" -eq 3 ] || fail "the example scenes: $(cat "$T/examples.txt")"
if [ "${SW_LCM:-0}" = 1 ]; then
    [ -e /usr/share/swaywatch/lcmtypes/state_t.lcm ] || fail "no LCM definitions"
fi
if [ -n "$mpi" ]; then
    /usr/bin/swaywatch-mpi replay "$E/hard-stop-overturn.csv" --scene "$E/crate.ini" -q ||
        fail "the installed swaywatch-mpi"
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
for f in /usr/bin/swaywatch /usr/bin/swaywatch-mpi /usr/share/swaywatch /usr/share/doc/swaywatch \
    "$U"; do
    [ ! -e "$f" ] || fail "$f left behind"
done
echo "deb.sh: ok"
