# SPDX-License-Identifier: GPL-3.0-or-later
# gnuplot_strings.sh - no byte of a string that reaches gnuplot can run a
# gnuplot command.  Every control byte (1-31, 127), both quotes, the
# backslash, '`', '$' and a byte that is not UTF-8 (0xff) is put, each
# followed by system("touch PWNED_xx"), into the log's file name, the
# figure's file name, a package name (printable bytes only: the scene
# refuses control characters) and boundary's --title, and replay --plot,
# simulate --plot, forensics --plot and --report and boundary --plot are
# run.  No PWNED_ file may appear, gnuplot must not fail, and the figure
# must be written under its exact name, also where a control byte in it is
# followed by a digit.
. "$(dirname "$0")/lib.sh"
command -v gnuplot >/dev/null 2>&1 || exit 77
LOGS=$SRC/sample_logs

python3 - "$SW" "$LOGS" "$TMP" <<'PY' || fail "a string reached gnuplot as a command"
import os, shutil, subprocess, sys

sw, logs, tmp = sys.argv[1].encode(), sys.argv[2].encode(), sys.argv[3].encode()
work = os.path.join(tmp, b"work")
os.mkdir(work)
scene = os.path.join(logs, b"crate.ini")
log = os.path.join(logs, b"hard-stop-overturn.csv")

special = list(range(1, 32)) + [127, ord("'"), ord('"'), ord("\\"), ord("`"), ord("$"), 0xFF]


def payload(b):
    return bytes([b]) + b'system("touch PWNED_%02x")' % b + bytes([b])


# file names: a few bytes each (a name is at most 255 bytes)
groups = [special[i:i + 6] for i in range(0, len(special), 6)]
failures = []


def run(args, what, out=None):
    r = subprocess.run([sw] + args, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if r.returncode not in (0, 1):
        failures.append("%s: exit %d: %s" % (what, r.returncode, r.stderr[-600:]))
    if b"gnuplot" in r.stderr and b"line" in r.stderr:
        failures.append("%s: gnuplot complained: %s" % (what, r.stderr[-600:]))
    if out is not None:
        if os.path.exists(out):
            os.unlink(out)
        else:
            failures.append("%s: %r was not written: %s" % (what, out, r.stderr[-600:]))
    return r


for n, grp in enumerate(groups):
    name = b"log" + b"".join(payload(b) for b in grp) + b".csv"
    path = os.path.join(work, name)
    shutil.copy(log, path)
    fig = os.path.join(work, b"fig" + b"".join(bytes([b]) for b in grp if b != ord("/")) + b".svg")
    run([b"replay", path, b"-s", scene, b"--plot", fig, b"-q"], "replay --plot, group %d" % n,
        fig)
    run([b"forensics", path, b"-s", scene, b"--no-what-if", b"--plot", fig, b"-q"],
        "forensics --plot, group %d" % n, fig)
    rep = os.path.join(work, b"rep%d.html" % n)
    run([b"forensics", path, b"-s", scene, b"--no-what-if", b"--report", rep, b"-q"],
        "forensics --report, group %d" % n, rep)
    os.unlink(path)

# a control byte followed by an octal digit: gnuplot reads "\0015" as one
# escape (a carriage return), so the figure went to another name
for b in (1, 7, 10, 27, 31):
    fig = os.path.join(work, b"fig" + bytes([b]) + b"5" + bytes([b]) + b"07.svg")
    run([b"replay", log, b"-s", scene, b"--plot", fig, b"-q"],
        "replay --plot, byte %d then digits in the name" % b, fig)

# titles: every byte in one --title (it is not a file name)
title = b"T" + b"".join(payload(b) for b in special)
fig = os.path.join(work, b"boundary.svg")
run([b"boundary", b"-s", scene, b"--pulse", b"half-sine", b"--omega-ratio", b"2:4:2", b"--title", title,
     b"--plot", fig, b"-q"], "boundary --title", fig)

# package names (at most 63 bytes): one per printable byte that quotes or
# escapes
for b in [b for b in special if 32 <= b < 127]:
    pname = b"P" + payload(b)
    for cmd in ([b"replay", log], [b"forensics", log, b"--no-what-if"]):
        fig = os.path.join(work, b"pkg.svg")
        run(cmd + [b"-s", scene, b"--set", b"package.name=" + pname, b"--plot", fig, b"-q"],
            "%s with package name %r" % (cmd[0].decode(), pname), fig)
    fig = os.path.join(work, b"sim.svg")
    run([b"simulate", b"-s", scene, b"--set", b"package.name=" + pname, b"--pulse",
         b"half-sine", b"--amplitude", b"-0.5g", b"--pulse-duration", b"0.5s", b"--plot", fig,
         b"-q"], "simulate with package name %r" % pname, fig)

pwned = [f for f in os.listdir(work) if f.startswith(b"PWNED")]
pwned += [f for f in os.listdir(tmp) if f.startswith(b"PWNED")]
if pwned:
    failures.append("gnuplot ran injected commands: %r" % pwned)
for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
PY
echo "gnuplot strings: no command from any byte"
