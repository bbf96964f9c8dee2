# SPDX-License-Identifier: GPL-3.0-or-later
"""field_check.py - the checks of field.sh on what the drive sent (feed.txt),
what the monitor said (monitor.err) and what it published (output.lcmlog,
recorded by lcm-logger).  Prints what it found; exit 1 on any failure.

usage: field_check.py WORK MON_RC RSS_WARM RSS_END RSS_BOUND UDP_DROPS PROBES
                      RESUME ASAN   (PYTHONPATH: the generated Python types)
"""
import re
import struct
import sys

from swaywatch import alarm_t, state_t

(work, mon_rc, warm, end, bound, drops, probes, resume, asan) = (
    sys.argv[1], *map(int, sys.argv[2:10]))
problems = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        problems.append(what)


# ---- what was sent --------------------------------------------------------
sent, events = {}, []
for line in open(work + "/feed.txt"):
    f = line.split()
    if f[0] == "event":
        events.append({"k": int(f[1]), "kind": f[2], "arg": float(f[3]),
                       "wall": int(f[4]), "u_after": int(f[5])})
    elif len(f) == 2:
        sent[f[0]] = int(f[1])
sent["published"] += probes
sent["decode"] += probes

# ---- what the monitor said ------------------------------------------------
err = open(work + "/monitor.err").read()
m = re.search(r"received (\d+) = accepted (\d+) \+ rejected (\d+)(?: \(([^)]*)\))?; "
              r"lost (-?\d+) \(by seq\), seq restarts (\d+), gaps (\d+), sensor restarts (\d+), "
              r"clock steps (\d+); published (\d+) states \((\d+) withheld\), (\d+) alarms "
              r"\((\d+) more folded", err)
check(mon_rc == 0, "the monitor ran to SIGINT and exited 0 (status %d)" % mon_rc)
if not m:
    check(False, "the monitor printed its final accounting")
    sys.exit(1)
received, accepted, rejected = int(m.group(1)), int(m.group(2)), int(m.group(3))
by = {}
for part in (m.group(4) or "").split(", "):
    if part:
        name, n = part.rsplit(" ", 1)
        by[name] = int(n)
lost, restarts, clock_steps = int(m.group(5)), int(m.group(8)), int(m.group(9))
folded = int(m.group(13))
kd = re.search(r"; (\d+) datagrams dropped by the kernel", err)
if kd:  # the monitor's own socket: any channel, its own states looped back too
    drops = int(kd.group(1))
print("sent %s\nmonitor: received %d = accepted %d + rejected %d %s; lost %d, sensor restarts "
      "%d, clock steps %d, alarms folded %d; kernel UDP drops %d"
      % (sent, received, accepted, rejected, by, lost, restarts, clock_steps, folded, drops))
check(received == accepted + rejected and rejected == sum(by.values()),
      "received = accepted + rejected by reason, nothing held at the stop")
check(0 <= sent["published"] - received <= drops,
      "received %d of %d published, the rest dropped by the kernel (%d)"
      % (received, sent["published"], drops))
if drops == 0:
    for r in ("decode", "trailing", "nonfinite", "implausible"):
        check(by.get(r, 0) == sent.get(r, 0),
              "refused as %s: %d, sent %d" % (r, by.get(r, 0), sent.get(r, 0)))
    # a late or repeated copy next to a sample held for confirmation may be
    # refused under another of these names; each is refused once (a forged
    # sample on a second sender's seq numbers as contested)
    timing = ("duplicate", "out_of_order", "jump", "time", "overload", "contested")
    # while the forger sends, a loaded machine delivers its samples in the
    # same bursts as the genuine ones, and it may hold the kept timeline
    # for a while: then genuine samples are refused for their time (and
    # evaluated by the second engines, the input contested), at most as
    # many as the forger's stretch holds
    forging = sum(int(e["arg"] * 1000) for e in events if e["kind"] == "forge")
    taken = sum(by.get(r, 0) for r in timing) - sum(sent.get(r, 0) for r in timing)
    check(0 <= taken <= forging,
          "refused for their time (%s): as many as sent, and %d genuine ones while forged "
          "samples competed (at most %d)" % (", ".join(timing), taken, forging))
    check(by.get("time", 0) >= sent["time"], "the INT64 utimes refused as time")
    # a machine that stalls over --max-backlog makes the monitor shed
    # (overload, counted): the only good samples it may miss, besides those
    check(0 <= sent["good"] - accepted - taken <= by.get("overload", 0),
          "accepted %d, good sent %d, shed %d, refused while contested %d"
          % (accepted, sent["good"], by.get("overload", 0), taken))
# the seq INT64_MIN sample is "no seq": the one after it shows a gap of one
check(sent["skipped"] <= lost <= sent["skipped"] + 1 + drops + by.get("overload", 0),
      "lost by seq %d: the outage's %d samples (and drops)" % (lost, sent["skipped"]))
check(restarts >= 1 and clock_steps >= 1, "the sensor restart and the clock step were seen")

# ---- what it published ----------------------------------------------------
states, alarms, flights = {}, [], set()
with open(work + "/output.lcmlog", "rb") as f:
    while (h := f.read(28)) and len(h) == 28:
        _, _, ts, cl, dl = struct.unpack(">IqqII", h)
        ch, data = f.read(cl).decode(), f.read(dl)
        if ch == "SWAY_STATE":
            s = state_t.decode(data)
            # a package's planes apart: each has its states and its alarm limit
            name = bytes(b & 0xFF for b in s.name).split(b"\0")[0].decode() + \
                (":lateral" if s.plane == state_t.PLANE_LATERAL else "")
            states.setdefault(name, []).append((ts, s.utime))
        elif ch == "SWAY_ALARM":
            a = alarm_t.decode(data)
            name = bytes(b & 0xFF for b in a.name).split(b"\0")[0].decode() + \
                (":lateral" if a.plane == alarm_t.PLANE_LATERAL else "")
            text = bytes(b & 0xFF for b in a.text).split(b"\0")[0].decode()
            # INPUT_REJECTED is limited per reason: the reason is part of its key
            why = re.search(r"rejected: (\w+)", text) if a.kind == alarm_t.KIND_INPUT_REJECTED \
                else None
            alarms.append((ts, name, (a.kind, why.group(1) if why else "")))
            if a.kind == alarm_t.KIND_MODEL_FAULT and "free flight" in text:
                flights.add(name)
out = {l.split()[0]: int(l.split()[1]) for l in open(work + "/output.txt")
       if len(l.split()) == 2}
check(out["nonfinite"] == 0 and out["undecodable"] == 0,
      "no non-finite number published (%d states, %d alarms recorded)"
      % (out["states"], out["alarms"]))
check(set(states) >= {"crate-A-bare", "crate-A-stiff-cushion"}, "states of both packages")

# every package resumes after every fault within RESUME samples; samples
# the kernel dropped (a flood overflows the socket) never reached the
# monitor, so a fault may be followed by up to that many more
for e in events:
    target = e["u_after"] + (int(e["arg"] * 1e6) if e["kind"] == "fall" else 0)
    for name, st in sorted(states.items()):
        after = [u for ts, u in st if ts >= e["wall"] and target <= u <= target + 5000000]
        delay = (min(after) - target) / 1000.0 if after else float("inf")
        check(delay <= resume + drops,
              "%s after %s at sample %d: states again within %g samples (limit %d + %d dropped "
              "by the kernel)" % (name, e["kind"], e["k"], delay, resume, drops))

# no silence outside the outage and the second of free fall
quiet = [(e["wall"] - 500000, e["wall"] + int(e["arg"] * 1e6) + 1500000)
         for e in events if e["kind"] in ("pause", "fall")]
for name, st in sorted(states.items()):
    ts = sorted(t for t, _ in st)
    worst = 0
    for a, b in zip(ts, ts[1:]):
        if b - a > worst and not any(lo <= a <= hi or lo <= b <= hi for lo, hi in quiet):
            worst = b - a
    check(worst <= 2500000, "%s: longest silence %.3f s" % (name, worst / 1e6))

# alarms rate-limited: at most 8 of a package and kind (and refusal reason)
# in any second
worst, worst_key = 0, None
by_key = {}
for ts, name, kind in alarms:
    by_key.setdefault((name, kind), []).append(ts)
for key, ts in by_key.items():
    ts.sort()
    j = 0
    for i in range(len(ts)):
        while ts[i] - ts[j] >= 1000000:
            j += 1
        if i - j + 1 > worst:
            worst, worst_key = i - j + 1, key
check(worst <= 8, "at most 8 alarms of a package and kind in a second (%d: %s)"
      % (worst, worst_key))
# the forger: the input contested at once, at critical level
for e in events:
    if e["kind"] == "forge":
        raised = [ts for ts, _, k in alarms if k[0] == alarm_t.KIND_INPUT_CONTESTED]
        check(any(ts >= e["wall"] for ts in raised),
              "the forger raised INPUT_CONTESTED (%d published)" % len(raised))
    if e["kind"] == "fifo":
        gaps = [ts for ts, _, k in alarms if k[0] == alarm_t.KIND_SENSOR_GAP
                and e["wall"] <= ts <= e["wall"] + int(e["arg"] * 1e6) + 500000]
        check(len(gaps) <= 1, "FIFO reads: %d SENSOR_GAP alarms (at most the first batch's)"
              % len(gaps))
# the second of free fall: a package flies for longer than the model can
# follow, and says so (fail safe) in a critical alarm while in the air
# (one that overturned before it lies still)
check(len(flights) >= 1, "a package raised its free-flight alarm (%s)" % sorted(flights))
check(folded > 0, "the alarm storms were folded (%d)" % folded)

# memory
if asan:
    print("skip memory: AddressSanitizer's quarantine grows by design")
else:
    check(end <= warm + bound, "VmRSS %d kB after 10 s, %d kB at the end (bound +%d kB)"
          % (warm, end, bound))
sys.exit(1 if problems else 0)
