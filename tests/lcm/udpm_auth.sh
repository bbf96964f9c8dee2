#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Integration over UDP multicast: a monitor with a key file (--key) while a
# sender without a key publishes quiet samples among the sensor's, which
# signs a braking that overturns the crate.  Every unsigned sample is
# refused (unauthenticated) and INPUT_CONTESTED raised at critical level;
# the signed braking raises TIP and OVERTURNED.  Then a change of key
# without a restart: keygen -o adds key 2, SIGHUP, the sensor signs with
# key 2 (the last of its file) and is taken; a key file others can read,
# SIGHUP: not applied; key 1 deleted from the monitor's file, SIGHUP, a
# sender still on key 1 is refused (unknown_key).
# The stop line counts each reason and says where the refused came from.
# usage: udpm_auth.sh SWAYWATCH SW_LCM_TOOL SCENE PORT
set -eu
. "$(dirname "$0")/netns.sh"
SW=$1 TOOL=$2 SCENE=$3 PORT=$4
URL="udpm://239.255.76.67:$PORT?ttl=0&recv_buf_size=2097152"

"$SW" keygen -o "$T/keys" 2>/dev/null
cp "$T/keys" "$T/old-sender"
"$SW" monitor -l "$URL" --scene "$SCENE" --key "$T/keys" --status 0.5 2>"$T/m.err" &
MON=$!
PIDS="$MON"
wait_subscribed 2
"$TOOL" publish "$URL" --rate 500 --duration 3 --amplitude 0 &
FORGER=$!
PIDS="$PIDS $FORGER"
"$TOOL" publish "$URL" --rate 500 --duration 3 --amplitude -9 --omega 5 --key "$T/keys"
wait "$FORGER" || fail "the forger"
wait_for "$T/m.err" 'accepted 1501, rejected 1501 (unauthenticated 1501)'
wait_for "$T/m.err" 'unauthentic 1501 in 1 bursts (the last: message '
for kind in 'level=critical package=crate-A kind=tip' \
    'level=critical package=crate-A kind=overturned' \
    'level=critical package=- kind=input_contested'; do
    grep -q "swaywatch: alarm .* $kind " "$T/m.err" || fail "no alarm line with $kind"
done
grep -q 'kind=input_contested .*text="unauthentic accel samples on ACCEL (unauthenticated)' \
    "$T/m.err" || fail "the contest's text"

# A new key, the monitor first; the sensor then signs with it.
"$SW" keygen -o "$T/keys" 2>/dev/null
kill -HUP "$MON"
wait_for "$T/m.err" "reload: 2 keys from $T/keys (id 1, 2)"
"$TOOL" publish "$URL" --rate 500 --duration 1 --amplitude 0 --key "$T/keys"
wait_for "$T/m.err" 'accepted 2002, '
# A key file others can read is not applied: the keys of before stay.
chmod 644 "$T/keys"
kill -HUP "$MON"
wait_for "$T/m.err" 'scene and key files not applied; going on with the scenes and keys of before'
chmod 600 "$T/keys"
# The old key out of the monitor's file: a sender still on it is refused.
sed -n 2p "$T/keys" >"$T/new"
chmod 600 "$T/new"
mv "$T/new" "$T/keys"
kill -HUP "$MON"
wait_for "$T/m.err" "reload: 1 key from $T/keys (id 2)"
"$TOOL" publish "$URL" --rate 500 --duration 0.2 --amplitude 0 --key "$T/old-sender"
wait_for "$T/m.err" 'unknown_key 101)'
kill -INT "$MON"
wait "$MON" || fail "monitor exited with $?"
cat "$T/m.err"
grep -q 'received 3604 = accepted 2002 + rejected 1602 (unauthenticated 1501, unknown_key 101)' \
    "$T/m.err" || fail "the stop line's counts"
grep -q 'swaywatch: monitor: authentication: 3604 checked, 2002 authentic, 1602 refused (the first: message [0-9]* on ACCEL, unauthenticated; the last: message 3604 on ACCEL, unknown_key (key 1)); [0-9]* times unauthentic samples began to arrive' \
    "$T/m.err" || fail "the stop line's authentication"
echo "ok: a keyed monitor ignored an unsigned sender and changed keys on SIGHUP"
