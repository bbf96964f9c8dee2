#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Authenticated sensors from the command (docs/security.md): swaywatch
# keygen and the key files it writes; a key file others can read (or its
# group write), a FIFO, a bad line: refused with the reason; replay --key
# of lcm-logger files: a signed log read as the unsigned one, issue 24's
# interleaving forgery and replayed copies spliced into it refused and
# counted (TIP, OVERTURNED and a critical INPUT_CONTESTED published), a log
# of a sender without a key or under another key refused with the reason
# and the way to read it; csv2lcmlog.py --key signs (in Python) what the
# monitor core checks (in C), and without a key writes the old layout.
# usage: auth_cli.sh SWAYWATCH SW_LCM_TOOL SCENE SOURCE_DIR PYTHON_DIR
set -eu
SW=$1 TOOL=$2 SCENE=$3 SRC=$4 PYDIR=$5
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ -f "$T/err" ] && sed 's/^/  | /' "$T/err" >&2
    exit 1
}
# run EXPECTED_RC CMD...: stdout in $T/out, stderr in $T/err
run() {
    want=$1
    shift
    rc=0
    "$@" >"$T/out" 2>"$T/err" || rc=$?
    [ "$rc" -eq "$want" ] || fail "$*: exit $rc, expected $want"
}
has() { grep -q -- "$1" "$T/err" || fail "no '$1' in the messages of: $2"; }
verdict() {
    python3 -c 'import json,sys; p=json.load(open(sys.argv[1]))["packages"][0]; print(p["verdict"], p["overturned"], repr(p["max_abs_theta"]), repr(p["overturn_time"]))' "$1"
}

# ---- keygen and key files --------------------------------------------------------
umask 022 # the usual one: keygen must not depend on it
run 0 "$SW" keygen -o "$T/keys"
[ "$(stat -c %a "$T/keys")" = 600 ] || fail "keygen -o made mode $(stat -c %a "$T/keys")"
grep -Eqx '1 HMAC-SHA256 HEX:[0-9a-f]{64}' "$T/keys" || fail "key line: $(cat "$T/keys")"
run 0 "$SW" keygen -o "$T/keys"
[ "$(wc -l <"$T/keys")" -eq 2 ] && sed -n 2p "$T/keys" | grep -Eqx '2 HMAC-SHA256 HEX:[0-9a-f]{64}' ||
    fail "the second key: $(cat "$T/keys")"
[ "$(cut -c20- "$T/keys" | sort -u | wc -l)" -eq 2 ] || fail "two keys alike"
run 2 "$SW" keygen -o "$T/keys" --id 2
has "key id 2 is in it already" "keygen --id of a key there"
run 0 "$SW" keygen --id 9
grep -Eqx '9 HMAC-SHA256 HEX:[0-9a-f]{64}' "$T/out" || fail "keygen --id 9: $(cat "$T/out")"
"$SW" keygen >"$T/world" 2>"$T/err"
has "standard output is a file others can read" "keygen > a file of mode 644"
run 2 "$SW" keygen --id 256
run 2 "$SW" keygen extra

# the sender's file: one key of its own, the monitor's: that one and another
head -n 1 "$T/keys" >"$T/k1"
chmod 600 "$T/k1"
"$TOOL" mklog "$T/plain.lcmlog" --rate 500 --duration 3 --amplitude -9 --omega 5
"$TOOL" mklog "$T/signed.lcmlog" --rate 500 --duration 3 --amplitude -9 --omega 5 --key "$T/k1"
cp "$T/keys" "$T/perm"
for mode in 644 604 602 620 666; do
    chmod "$mode" "$T/perm"
    run 2 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --key "$T/perm"
    has "permissions 0$mode are too open" "--key of mode $mode"
    has "chmod 600" "--key of mode $mode"
done
chmod 640 "$T/perm" # a group of the monitor's user: allowed
run 0 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --key "$T/perm" -q
run 3 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --key "$T/none"
has "cannot open" "--key of a missing file"
mkfifo "$T/fifo"
run 2 timeout 10 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --key "$T/fifo"
has "not a regular file" "--key of a FIFO"
printf '# keys\n1 HMAC-SHA256 HEX:0011\n' >"$T/short"
chmod 600 "$T/short"
run 2 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --key "$T/short"
has "$T/short:2: the key is not HEX: and 64 hexadecimal digits" "--key of a short key"
grep -q 0011 "$T/err" && fail "the key was quoted"
run 2 "$SW" keygen -o "$T/short"
has "$T/short:2:" "keygen -o onto a bad key file"
printf 't,a\n0,0\n0.001,0\n' >"$T/log.csv"
run 2 "$SW" replay "$T/log.csv" --scene "$SCENE" --key "$T/k1"
has "option '--key' is for lcm-logger files" "--key on a CSV log"
chmod 644 "$T/k1"
run 2 "$SW" monitor --scene "$SCENE" --key "$T/k1" --lcm-url "file://$T/signed.lcmlog?speed=0"
has "permissions 0644 are too open" "monitor --key of mode 644"
chmod 600 "$T/k1"

# ---- replay --key -----------------------------------------------------------------
run 0 "$SW" replay "$T/plain.lcmlog" --scene "$SCENE" --json
cp "$T/out" "$T/plain.json"
run 0 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --json --key "$T/keys"
cp "$T/out" "$T/signed.json"
has "authentication: 1501 checked, 1501 authentic, 0 refused" "replay --key of a signed log"
[ "$(verdict "$T/signed.json")" = "$(verdict "$T/plain.json")" ] ||
    fail "signed and unsigned logs differ: $(verdict "$T/signed.json") / $(verdict "$T/plain.json")"
verdict "$T/signed.json" | grep -q '^overturned True' || fail "the drive does not overturn"
run 0 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --json
has "1501 samples carry a MAC that was not checked: give the sender's key file (--key FILE)" \
    "replay of a signed log without --key"
run 2 "$SW" replay "$T/plain.lcmlog" --scene "$SCENE" --key "$T/keys"
has "rejected 1501 (unauthenticated 1501)" "replay --key of an unsigned log"
has "every sample is unauthenticated (no MAC: written by a sender without a key); without --key" \
    "replay --key of an unsigned log"
"$SW" keygen -o "$T/other" 2>/dev/null
run 2 "$SW" replay "$T/signed.lcmlog" --scene "$SCENE" --key "$T/other"
has "rejected 1501 (bad_mac 1501)" "replay under another key"
has "signed by another key (unknown_key, bad_mac); give --key the key file of the sender" \
    "replay under another key"

# Issue 24's forgery spliced into the signed log: after every second
# genuine sample a quiet one stamped 2.5 ms ahead (half without a MAC, half
# in the old layout), and every fifth genuine message played again 20 ms
# late, bytes and all.
PYTHONPATH=$PYDIR python3 - "$T/signed.lcmlog" "$T/forged.lcmlog" <<'PY'
import struct, sys
from swaywatch import accel_t, accel_v1_t
events = []
with open(sys.argv[1], "rb") as f:
    while True:
        h = f.read(28)
        if len(h) < 28:
            break
        _, num, ts, cl, dl = struct.unpack(">IqqII", h)
        ch = f.read(cl)
        events.append((ts, ch, f.read(dl)))
out = []
def put(ts, ch, data):
    out.append(struct.pack(">IqqII", 0xEDA1DA01, len(out), ts, len(ch), len(data)) + ch + data)
for i, (ts, ch, data) in enumerate(events):
    put(ts, ch, data)
    g = accel_t.decode(data)
    if i % 2 == 1:
        f = accel_t() if i % 4 == 1 else accel_v1_t()
        f.utime, f.seq, f.ax = g.utime + 2500, g.seq, 0.0
        put(ts, ch, f.encode())
    if i >= 10 and i % 5 == 0:
        put(ts, ch, events[i - 10][2])
open(sys.argv[2], "wb").write(b"".join(out))
print("forged %d, replayed %d" % (sum(1 for i in range(len(events)) if i % 2 == 1),
                                  sum(1 for i in range(10, len(events)) if i % 5 == 0)))
PY
run 0 "$SW" replay "$T/forged.lcmlog" --scene "$SCENE" --json --key "$T/keys" \
    --publish "file://$T/pub.lcmlog?mode=w" --speed 0
cp "$T/out" "$T/forged.json"
has "accepted 1501 + rejected 1049 (unauthenticated 750, replayed 299)" "the forged log's counts"
has "authentication: 2550 checked, 1501 authentic, 1049 refused (the first: message 3 on ACCEL, unauthenticated; the last: message 2550 on ACCEL, replayed (key 1))" \
    "the forged log's authentication line"
[ "$(verdict "$T/forged.json")" = "$(verdict "$T/signed.json")" ] ||
    fail "the forgery changed the verdict: $(verdict "$T/forged.json")"
"$TOOL" dump "$T/pub.lcmlog" >"$T/pub.txt"
grep -q '^alarm [0-9]* crate-A 5 2 ' "$T/pub.txt" || fail "no TIP published"
grep -q '^alarm [0-9]* crate-A 6 2 ' "$T/pub.txt" || fail "no OVERTURNED published"
grep -q '^alarm [0-9]* - 13 2 unauthentic accel samples on ACCEL (unauthenticated)' "$T/pub.txt" ||
    fail "no critical INPUT_CONTESTED published"
# without --key the same log is refused (41 % of its samples refused) with the option
run 2 "$SW" replay "$T/forged.lcmlog" --scene "$SCENE" --json
has "samples carry a MAC that was not checked" "replay of the forged log without --key"

# ---- csv2lcmlog.py ------------------------------------------------------------------
printf 'time,accel\n' >"$T/drive.csv"
python3 -c 'import math
for k in range(2001):
    t = k / 500
    a = -9 * math.sin(5 * (t - 0.2)) if 0.2 <= t <= 0.2 + math.pi / 5 else 0.0
    print("%.3f,%.6f" % (t, a))' >>"$T/drive.csv"
PYTHONPATH=$PYDIR python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/drive.csv" "$T/py-signed.lcmlog" \
    --key "$T/k1" >/dev/null
run 0 "$SW" replay "$T/py-signed.lcmlog" --scene "$SCENE" --json --key "$T/keys"
has "authentication: 2001 checked, 2001 authentic, 0 refused" "replay --key of csv2lcmlog.py --key"
PYTHONPATH=$PYDIR python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/drive.csv" "$T/py-plain.lcmlog" \
    >/dev/null
[ "$(python3 -c 'import struct,sys; d=open(sys.argv[1],"rb").read(28); print(struct.unpack(">IqqII", d)[4])' "$T/py-plain.lcmlog")" = 48 ] ||
    fail "csv2lcmlog.py without a key: not the old layout"
run 2 "$SW" replay "$T/py-plain.lcmlog" --scene "$SCENE" --key "$T/keys"
has "unauthenticated 2001" "replay --key of csv2lcmlog.py without a key"
chmod 644 "$T/k1"
rc=0
PYTHONPATH=$PYDIR python3 "$SRC/docs/examples/csv2lcmlog.py" "$T/drive.csv" "$T/x.lcmlog" \
    --key "$T/k1" >/dev/null 2>"$T/err" || rc=$?
[ "$rc" -ne 0 ] && has "too open" "csv2lcmlog.py --key of mode 644" ||
    fail "csv2lcmlog.py took a key file others can read"
echo "ok: keygen, key files, replay --key, csv2lcmlog.py --key"
