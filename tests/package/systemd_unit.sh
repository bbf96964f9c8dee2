#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# The systemd unit of the monitor: systemd accepts it (when systemd-analyze
# is there), it runs no root process, it is a notify service with a
# watchdog that is restarted on failure, and its ExecStart, run by the shell as
# systemd would run it, starts 'swaywatch monitor' with one --scene per
# scene file and the options of /etc/default/swaywatch.  The source is a
# template: the install fills in the folder of the command (@SW_BINDIR@), so
# that the unit runs its own installation's swaywatch by full path, never
# one found earlier in PATH.
# usage: systemd_unit.sh UNIT_TEMPLATE
set -eu
IN=$1
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "systemd_unit.sh: $*" >&2; exit 1; }

grep -q '^ExecStart=.*exec @SW_BINDIR@/swaywatch monitor ' "$IN" ||
    fail "ExecStart does not run @SW_BINDIR@/swaywatch by full path"
# The unit as the package installs it.
UNIT=$T/swaywatch-monitor.service
sed 's|@SW_BINDIR@|/usr/bin|g' "$IN" >"$UNIT"
if grep -q '@[A-Z_]*@' "$UNIT"; then fail "placeholder left: $(grep '@[A-Z_]*@' "$UNIT")"; fi

if command -v systemd-analyze >/dev/null 2>&1; then
    # --man=no: the manual pages it names are installed with the package.
    systemd-analyze verify --man=no "$UNIT" || fail "systemd-analyze verify"
else
    echo "systemd_unit.sh: no systemd-analyze: only the static checks"
fi
for line in DynamicUser=yes Restart=on-failure 'ExecReload=/bin/kill -HUP $MAINPID' \
    RestartPreventExitStatus=2 EnvironmentFile=-/etc/default/swaywatch \
    Type=notify NotifyAccess=main WatchdogSec=10s StartLimitIntervalSec=0; do
    grep -qxF "$line" "$UNIT" || fail "no '$line'"
done
if grep -Eq '^(User=root|AmbientCapabilities=.)' "$UNIT"; then fail "runs with privileges"; fi

# ExecStart through the shell: '$$' is systemd's escape of '$'; the scene
# folder is replaced by a scratch folder, and the command by a stand-in that
# prints its arguments one per line, "installed" in $T/bin; another
# stand-in, first in PATH, must not be the one that runs.
mkdir -p "$T/etc/swaywatch" "$T/bin" "$T/path"
touch "$T/etc/swaywatch/a.ini" "$T/etc/swaywatch/b.ini" "$T/etc/swaywatch/README"
printf '#!/bin/sh\nfor a; do printf "%%s\\n" "$a"; done\n' >"$T/bin/swaywatch"
printf '#!/bin/sh\necho "the swaywatch first in PATH ran"\n' >"$T/path/swaywatch"
chmod +x "$T/bin/swaywatch" "$T/path/swaywatch"
cmd=$(sed -n "s|@SW_BINDIR@|$T/bin|g; s/^ExecStart=//p" "$IN")
[ -n "$cmd" ] || fail "no ExecStart"
cmd=$(printf '%s\n' "$cmd" | sed "s|\\\$\\\$|\$|g; s|/etc/swaywatch|$T/etc/swaywatch|g")
# systemd splits ExecStart like a shell: the quoted script is one word.
eval "set -- $cmd"
[ "$1" = /bin/sh ] && [ "$2" = -c ] || fail "ExecStart is not '/bin/sh -c SCRIPT': $cmd"
out=$(PATH="$T/path:$PATH" SWAYWATCH_MONITOR_OPTS="--axis y --status 60" /bin/sh -c "$3")
want="monitor
--scene
$T/etc/swaywatch/a.ini
--scene
$T/etc/swaywatch/b.ini
--axis
y
--status
60"
[ "$out" = "$want" ] || fail "ExecStart ran: $(echo $out)"
echo "systemd_unit.sh: ok"
