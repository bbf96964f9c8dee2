#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# 'cmake --install' into a scratch prefix puts every piece in place, and a
# program builds and runs against the installed library through
# pkg-config, shared and static; the uninstall script removes it all again.
# The build folder's install_manifest.txt (by which a real install from
# there is uninstalled) is put back as it was.
# usage: install.sh BUILD_DIR SOURCE_DIR   (env: SW_VERSION, SW_LCM, SW_MAN, SW_CC_FLAGS)
set -eu
BUILD=$1 SRC=$(cd "$2" && pwd)
T=$(mktemp -d)
M=$(cd "$BUILD" && pwd)/install_manifest.txt
if [ -e "$M" ]; then cp -p "$M" "$T/manifest.saved"; fi
restore() {
    if [ -e "$T/manifest.saved" ]; then cp -p "$T/manifest.saved" "$M"; else rm -f "$M"; fi
    rm -rf "$T"
}
trap restore EXIT
P=$T/prefix
fail() { echo "install.sh: $*" >&2; exit 1; }

cmake --install "$BUILD" --prefix "$P" >"$T/install.log"
cd "$P"
libdir=$(cd "$P" && ls -d lib/pkgconfig lib/*/pkgconfig 2>/dev/null | head -n 1 | sed 's|/pkgconfig$||')
[ -n "$libdir" ] || fail "no pkgconfig folder under $P/lib"
for f in bin/swaywatch "$libdir/libswaywatch.a" "$libdir/libswaywatch.so" \
    "$libdir/libswaywatch.so.0" "$libdir/pkgconfig/swaywatch.pc" \
    include/swaywatch/swaywatch.h include/swaywatch/engine.h \
    share/bash-completion/completions/swaywatch lib/systemd/system/swaywatch-monitor.service \
    share/doc/swaywatch/deployment.md share/doc/swaywatch/examples/tipcheck.c \
    share/doc/swaywatch/copyright; do
    [ -e "$f" ] || fail "not installed: $f"
done
grep -q '^License: GPL-3.0-or-later$' share/doc/swaywatch/copyright || fail "copyright: no licence"

# The unit runs this installation's command by full path.
U=lib/systemd/system/swaywatch-monitor.service
grep -q "^ExecStart=.*exec $P/bin/swaywatch monitor " "$U" ||
    fail "the unit's ExecStart does not name $P/bin/swaywatch: $(grep ExecStart "$U")"
grep -q "/$U\$" "$M" || fail "the unit is not in $M"
# A scratch libdir is not a folder of the linker's cache: no ldconfig, a note.
grep -q "is not a folder of the dynamic linker's cache" "$T/install.log" ||
    fail "no note about the linker's cache in the install log"

# The example scenes are valid and run on the sample drives.
E=share/swaywatch/examples
for s in crate.ini crate-on-frame.ini crate-on-cushion.ini; do
    [ -e "$E/$s" ] || fail "no example scene $s"
done
bin/swaywatch replay "$E/hard-stop-overturn.csv" --json --scene "$E/crate.ini" \
    --scene "$E/crate-on-frame.ini" --scene "$E/crate-on-cushion.ini" >"$T/examples.json" ||
    fail "replay of the installed examples"
python3 -c '
import json, sys
p = json.load(open(sys.argv[1]))["packages"]
assert [x["model"] for x in p] == ["bare", "frame", "cushion"], p
assert all(x["overturned"] for x in p)' "$T/examples.json" ||
    fail "the installed examples: unexpected summary"
[ "$(readlink "$libdir/libswaywatch.so")" = libswaywatch.so.0 ] ||
    fail "libswaywatch.so does not point to libswaywatch.so.0"
objdump -p "$libdir/libswaywatch.so.0" | grep -q 'SONAME *libswaywatch.so.0$' ||
    fail "SONAME of libswaywatch.so.0"
for h in "$SRC"/include/swaywatch/*.h; do
    [ -e "include/swaywatch/$(basename "$h")" ] || fail "header not installed: $h"
done
[ -e share/man/man5/swaywatch-scene.5 ] || fail "no swaywatch-scene.5"
if [ "${SW_MAN:-0}" = 1 ]; then
    [ -e share/man/man1/swaywatch.1 ] || fail "no swaywatch.1"
    # The hand-written EXAMPLES made it into the pages, and every page
    # points to the scene format.
    for h in "$SRC"/docs/man/swaywatch-*.h2m; do
        p=share/man/man1/$(basename "$h" .h2m).1
        grep -q '^\.SH EXAMPLES' "$p" || fail "no EXAMPLES in $p"
    done
    for p in share/man/man1/swaywatch*.1; do
        # A page that is a link (".so man1/swaywatch.1") is checked
        # through the page it names.
        so=$(sed -n '1s/^\.so //p' "$p")
        [ -z "$so" ] || p=share/man/$so
        grep -q 'swaywatch\\-scene (5)' "$p" || fail "no SEE ALSO swaywatch-scene(5) in $p"
    done
    for c in $(bin/swaywatch --help | awk '/^Commands:/ {on = 1; next}
                on && /^$/ {exit} on && /^  [a-z]/ {print $1}'); do
        [ -e "share/man/man1/swaywatch-$c.1" ] || fail "no manual page for '$c'"
        bin/swaywatch "$c" --version | grep -qx "swaywatch $c $SW_VERSION" ||
            fail "swaywatch $c --version"
    done
fi
if [ "${SW_LCM:-0}" = 1 ]; then
    for t in accel_t state_t alarm_t; do
        [ -e "share/swaywatch/lcmtypes/$t.lcm" ] || fail "no $t.lcm"
        [ -e "share/swaywatch/lcmtypes/c/swaywatch_$t.h" ] || fail "no C header of $t"
        [ -e "share/swaywatch/lcmtypes/python/swaywatch/$t.py" ] || fail "no Python $t"
    done
fi
bin/swaywatch --version | grep -qx "swaywatch $SW_VERSION" || fail "swaywatch --version"

# The LCM examples build and run on the installed bindings alone, by the
# lines their headers give, as installed (their /usr this prefix), run
# from another folder.
if [ "${SW_LCM:-0}" = 1 ]; then
    L=share/swaywatch/lcmtypes
    X=share/doc/swaywatch/examples
    mkdir "$T/elsewhere"
    sed -n 's/^ \*     //p' "$X/alarm_listener.c" | sed "s|/usr/|$P/|g" >"$T/elsewhere/build.sh"
    grep -q 'cc -o alarm_listener' "$T/elsewhere/build.sh" ||
        fail "no build line in the installed alarm_listener.c"
    (cd "$T/elsewhere" && sh -e build.sh) || fail "the build line of alarm_listener.c: $(cat "$T/elsewhere/build.sh")"
    "$T/elsewhere/alarm_listener" -h >/dev/null
    PYTHONPATH="$P/$L/python" python3 "$SRC/tests/package/mkaccel.py" "$T/elsewhere/drive.lcmlog" \
        --duration 0.1
    python3 - "$X/decode_states.py" "$P" >"$T/elsewhere/run.sh" <<'PY'
import re, sys
doc = open(sys.argv[1]).read().split('"""')[1]  # the docstring as the file has it
block = re.search(r"\n\n(    PYTHONPATH=.*?)\n\n", doc, re.S).group(1)
print(block.replace("\\\\\n", "\\\n").replace("/usr/", sys.argv[2] + "/"))
PY
    grep -q 'decode_states.py drive.lcmlog' "$T/elsewhere/run.sh" ||
        fail "no usage line in the installed decode_states.py"
    (cd "$T/elsewhere" && sh -e run.sh >/dev/null) ||
        fail "the usage line of decode_states.py: $(cat "$T/elsewhere/run.sh")"
fi

# The relocatable .pc file points into this prefix.
export PKG_CONFIG_PATH="$P/$libdir/pkgconfig"
pkg-config --exists --print-errors swaywatch
[ "$(pkg-config --modversion swaywatch)" = "$SW_VERSION" ] || fail "pkg-config --modversion"
cc ${SW_CC_FLAGS:-} -o "$T/tipcheck" "$SRC/docs/examples/tipcheck.c" $(pkg-config --cflags --libs swaywatch)
LD_LIBRARY_PATH="$P/$libdir" ldd "$T/tipcheck" | grep -q "$P/$libdir/libswaywatch.so.0" ||
    fail "tipcheck is not linked against the installed libswaywatch.so.0"
LD_LIBRARY_PATH="$P/$libdir" "$T/tipcheck"
# Static: the archive plus Libs.private and Requires.private.
libs=$(pkg-config --static --libs swaywatch | sed 's/-lswaywatch\b/-l:libswaywatch.a/')
cc ${SW_CC_FLAGS:-} -o "$T/tipcheck-static" "$SRC/docs/examples/tipcheck.c" $(pkg-config --cflags swaywatch) $libs
if ldd "$T/tipcheck-static" | grep -q libswaywatch; then fail "tipcheck-static uses the .so"; fi
"$T/tipcheck-static" >/dev/null

# Uninstall: every file of the manifest goes, and swaywatch's own folders.
cd "$T"
n=$(grep -c . "$M")
cmake -DSW_MANIFEST="$M" -P "$SRC/scripts/uninstall.cmake" >"$T/uninstall.log" ||
    { cat "$T/uninstall.log" >&2; fail "uninstall failed"; }
left=$(find "$P" ! -type d | head -n 5)
[ -z "$left" ] || fail "left after uninstall: $left"
for d in share/swaywatch share/doc/swaywatch include/swaywatch; do
    [ ! -e "$P/$d" ] || fail "folder left after uninstall: $d"
done
echo "install.sh: ok ($(wc -l <"$T/install.log") lines of install log, $n files uninstalled)"
