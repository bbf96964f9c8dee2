# SPDX-License-Identifier: GPL-3.0-or-later
# report.sh - "swaywatch forensics --report FILE.html": one self-contained
# page, checked as a browser renders it.  Headless Chromium loads it with
# the network cut off and scripts disabled, logs no console error, and
# the rendered DOM holds the answer, the log's facts, the figures (the
# whole drive and a close-up of each decisive moment, each with a caption
# that names exactly the panels drawn), the events, the what-if table, the
# limits and the fingerprint (the SHA-256 of the log and scenes as
# sha256sum gives them, the version and the command); its screenshot is
# not blank.  Then the times: a log with dates (epoch seconds) has its
# start, end and decisive moments in UTC, computed here from its first
# date; one without has none and says so; an lcm-logger file has them from
# the samples' utime, or from lcm-logger's own times when the utime counts
# from a sensor's boot (if the LCM build is there).  A log with a hole over
# the braking and unreadable rows says at the top that its verdict is
# incomplete, and lists the gap and the rows by reason with their lines.
# Skipped (77) where Chromium is not installed.
. "$(dirname "$0")/lib.sh"
LOGS=$SRC/sample_logs
CHROME=$(command -v chromium || command -v chromium-browser || true)
[ -n "$CHROME" ] || { echo "chromium not installed: skipped"; exit 77; }
command -v gnuplot >/dev/null 2>&1 || { echo "gnuplot not installed: skipped"; exit 77; }

run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$LOGS/crate.ini" \
    --scene "$LOGS/crate-on-frame.ini" --report "$TMP/incident.html" --json
expect_rc 0 "--report"
cp "$TMP/out" "$TMP/f.json"
[ -s "$TMP/incident.html" ] || fail "no report written"
# self-contained: nothing fetched, nothing run
grep -Eiq '<script|<link|<iframe|src="http|href="http|@import|url\(' "$TMP/incident.html" &&
    fail "the report refers to something outside itself or runs a script"

run "$SW" forensics "$LOGS/hard-stop-overturn.csv" --scene "$LOGS/crate.ini" --report "$TMP/x.txt"
expect_rc 2 "--report without .html"

# Chromium wants a writable home; no network, no scripts.
export HOME="$TMP"
FLAGS="--headless --no-sandbox --disable-gpu --disable-javascript --no-first-run \
--proxy-server=127.0.0.1:9 --proxy-bypass-list=<-loopback> --user-data-dir=$TMP/profile"
# render PAGE DOM: the page as Chromium renders it, with no console message
render() {
    # shellcheck disable=SC2086
    timeout 120 "$CHROME" $FLAGS --enable-logging=stderr --v=0 --dump-dom \
        "file://$1" >"$2" 2>"$TMP/chrome.err" ||
        { cat "$TMP/chrome.err" >&2; fail "chromium could not render $1"; }
    if grep -i 'CONSOLE' "$TMP/chrome.err"; then
        fail "console messages while rendering $1"
    fi
}
render "$TMP/incident.html" "$TMP/dom.html"
# shellcheck disable=SC2086
timeout 120 "$CHROME" $FLAGS --window-size=1200,2400 --screenshot="$TMP/shot.png" \
    "file://$TMP/incident.html" >/dev/null 2>"$TMP/chrome2.err" ||
    { cat "$TMP/chrome2.err" >&2; fail "chromium could not take a screenshot"; }

# The rendered page's text, element ids, figures and their captions, for
# the checks below (python3 page.py DOM).
cat >"$TMP/page.py" <<'PY'
import html.parser, re

class Page(html.parser.HTMLParser):
    """The text of a rendered page, its ids, and per <figure> its caption
    and the y labels of the panels its SVG draws."""
    def __init__(self, dom):
        super().__init__()
        self.parts, self.ids, self.figures, self.skip = [], {}, [], 0
        self.fig, self.cap, self.svgtext = None, None, None
        self.feed(dom)
        self.text = " ".join(" ".join(self.parts).split())
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids[a["id"]] = tag
        if tag in ("style", "title"):
            self.skip += 1
        if tag == "figure":
            self.fig = {"id": a.get("id"), "caption": "", "svg": ""}
        if tag == "figcaption":
            self.cap = []
        if tag == "svg" and self.fig is not None:
            self.svgtext = []
    def handle_endtag(self, tag):
        if tag in ("style", "title"):
            self.skip -= 1
        if tag == "figcaption" and self.fig is not None:
            self.fig["caption"] = " ".join(" ".join(self.cap).split())
            self.cap = None
        if tag == "svg" and self.svgtext is not None:
            self.fig["svg"] = " ".join(" ".join(self.svgtext).split())
            self.svgtext = None
        if tag == "figure" and self.fig is not None:
            self.figures.append(self.fig)
            self.fig = None
    def handle_data(self, d):
        if self.cap is not None:
            self.cap.append(d)
        if self.svgtext is not None:
            self.svgtext.append(d)
        if not self.skip:
            self.parts.append(d)

# a panel's y label in the SVG, and the words its caption uses for it
PANELS = [("bed acceleration", "the bed acceleration"), ("tilt θ / α", "the tilt θ"),
          ("margin to overturn", "the margin to overturn"), ("reserve (g)", "the reserve")]

def check_captions(page):
    """Every figure's caption names the panels its SVG draws, and only them."""
    for fig in page.figures:
        drawn = [cap for label, cap in PANELS if label in fig["svg"]]
        said = [cap for label, cap in PANELS if cap in fig["caption"]]
        assert drawn and drawn == said, (fig["id"], drawn, said, fig["caption"][:300])
        places = re.findall(r"(?:^|; |\. )(Top|second|third|middle|bottom): ", fig["caption"])
        assert len(places) == len(drawn), (fig["id"], places, len(drawn))
PY
LOG_SUM=$(sha256sum <"$LOGS/hard-stop-overturn.csv" | cut -d' ' -f1)
CRATE_SUM=$(sha256sum <"$LOGS/crate.ini" | cut -d' ' -f1)
FRAME_SUM=$(sha256sum <"$LOGS/crate-on-frame.ini" | cut -d' ' -f1)
LOG_SIZE=$(wc -c <"$LOGS/hard-stop-overturn.csv" | tr -d ' ')
python3 - "$TMP/dom.html" "$TMP/f.json" "$TMP/shot.png" "$LOG_SUM $CRATE_SUM $FRAME_SUM $LOG_SIZE" <<'PY' || fail "the rendered report"
import json, struct, sys, zlib
sys.path.insert(0, sys.argv[1].rsplit("/", 1)[0])
from page import Page, check_captions

dom, facts, shot = open(sys.argv[1]).read(), json.load(open(sys.argv[2])), sys.argv[3]
log_sum, crate_sum, frame_sum, log_size = sys.argv[4].split()
p = Page(dom)
text = p.text
want = ["Incident report", "crate-A", "crate-A-on-frame", "OVERTURNED", "Safety factor [",
        "It overturned", "The recording", "sample rate", "1000 Hz", "peak |bed acceleration|",
        "gaps", "Events", "uplift", "overturn", "What would have saved it", "as given",
        "frame, soft bearings", "cushion, firm", "Assumptions and limits", "swaywatch forensics",
        "hard-stop-overturn.csv", "--report", "Smallest reserve", "What was not used",
        "No sample was refused", "The moments that mattered", "Fingerprint"]
missing = [w for w in want if w not in text]
assert not missing, missing
assert {"answer-0", "answer-1", "log", "figure", "events", "times", "unused", "zoom-0",
        "fingerprint", "digests", "command", "version"} <= set(p.ids), p.ids
assert "incomplete" not in p.ids, "an incomplete banner on a complete log"
# the figures: the whole drive (four panels: the reserve is on) and a
# close-up of the overturns (both packages overturn within 3 s: one window,
# no margin panel), each with its caption
figs = {f["id"]: f for f in p.figures}
assert set(figs) == {"figure", "zoom-0"}, list(figs)
assert "reserve (g)" in figs["figure"]["svg"] and "margin to overturn" in figs["figure"]["svg"]
assert "margin to overturn" not in figs["zoom-0"]["svg"] and "reserve (g)" in figs["zoom-0"]["svg"]
check_captions(p)
z = figs["zoom-0"]["caption"]
for pk in facts["packages"]:
    assert "the overturn of %s at %.3f s" % (pk["name"], pk["overturn_time"]) in z, z[:400]
# a close-up is a few seconds: its time axis spans 6 s around the first overturn
t = min(pk["overturn_time"] for pk in facts["packages"])
assert "Close-up: %.3f s to" % (t - 3) in z, z[:200]
# the fingerprint, as sha256sum counts it
assert "log hard-stop-overturn.csv" in text or "hard-stop-overturn.csv %s %s" % (log_size, log_sum) in text
for digest in (log_sum, crate_sum, frame_sum):
    assert digest in text, digest
assert "%s %s" % (log_size, log_sum) in text, "the log's size and digest"
assert facts["build"]["text"] in text and facts["command_line"] in text
# no dates in this log: said, and no UTC anywhere
assert "none: the log's times count from an unknown start" in text
assert "no time of day can be given" in text and "UTC)" not in text
# the same numbers as --json: each package's bracket and verdict
for k, pk in enumerate(facts["packages"]):
    assert pk["safety_factor"]["text"] in text, pk["safety_factor"]["text"]
    assert pk["safety_factor"]["meaning"] in text
assert facts["swaywatch"] in text

# the screenshot: a PNG of the page, not blank (many pixels differ from
# the background, and several colours: text, the red of the verdict, the
# figure's lines)
data = open(shot, "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, w = 8, b"", 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and ctype in (2, 6), (depth, ctype)
        bpp = 3 if ctype == 2 else 4
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
stride = w * bpp
rows, prev = [], bytearray(stride)
i = 0
for y in range(h):
    f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
    i += 1 + stride
    for x in range(stride):
        a = line[x - bpp] if x >= bpp else 0
        b, c = prev[x], prev[x - bpp] if x >= bpp else 0
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(bytes(line))
    prev = line
colours, ink = set(), 0
for y in range(0, h, 3):
    r = rows[y]
    for x in range(0, w, 3):
        px = r[x * bpp:x * bpp + 3]
        colours.add(px)
        ink += px != b"\xff\xff\xff"
assert ink > 0.02 * (w // 3) * (h // 3), ("nearly blank", ink)
assert any(p[0] > 150 and p[1] < 80 and p[2] < 80 for p in colours), "no red verdict drawn"
assert len(colours) > 20, len(colours)
PY

# ---- a log with dates: epoch seconds from 2024-05-20T12:00:00Z ----
python3 - "$LOGS/hard-stop-overturn.csv" "$TMP/epoch.csv" <<'PY'
import sys
with open(sys.argv[1]) as i, open(sys.argv[2], "w") as o:
    o.write("time,accel\n")
    next(i)
    for line in i:
        t, a = line.strip().split(",")
        o.write("%.3f,%s\n" % (1716206400 + float(t), a))
PY
run "$SW" forensics "$TMP/epoch.csv" --scene "$LOGS/crate.ini" --no-what-if \
    --report "$TMP/epoch.html" --json
expect_rc 0 "--report of a log with dates"
cp "$TMP/out" "$TMP/epoch.json"
render "$TMP/epoch.html" "$TMP/epoch-dom.html"
# times(LABEL START_UTIME_US) for the checks of a page with dates
cat >"$TMP/times.py" <<'PY'
import datetime, json, sys
sys.path.insert(0, sys.argv[1].rsplit("/", 1)[0])
from page import Page, check_captions
p, j = Page(open(sys.argv[1]).read()), json.load(open(sys.argv[2]))
start_us = int(sys.argv[3])
t0 = datetime.datetime(1970, 1, 1, tzinfo=datetime.timezone.utc) + datetime.timedelta(microseconds=start_us)
def iso(s):
    return (t0 + datetime.timedelta(milliseconds=round(s * 1000))).strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"
text = p.text
check_captions(p)
assert "starts at (UTC) %s" % iso(0) in text, iso(0)
assert "ends at (UTC) %s" % iso(8) in text, iso(8)
r = j["replay"]["packages"][0]
for what, t in (("first uplift", r["uplift_time"]), ("tipped (|θ| = α)", r["tip_time"]),
                ("overturned", r["overturn_time"]), ("smallest reserve", r["min_reserve_time"])):
    assert "%s %.4f %s" % (what, t, iso(t)) in text, (what, t, iso(t))
assert "OVERTURNED at %.3f s (%s)" % (r["overturn_time"], iso(r["overturn_time"])) in text
z = [f for f in p.figures if f["id"] == "zoom-0"][0]["caption"]
t = r["overturn_time"]
assert "(%s to %s)" % (iso(t - 3), iso(t + 3)) in z, z[:300]
print("dates from:", j["log"]["dates_from"])
PY
python3 "$TMP/times.py" "$TMP/epoch-dom.html" "$TMP/epoch.json" 1716206400000000 ||
    fail "the UTC times of a log with dates"

# ---- a hole over the braking and unreadable rows: incomplete, said at the top ----
python3 - "$LOGS/braking-pothole.csv" "$TMP/hole.csv" <<'PY'
import sys
with open(sys.argv[1]) as i, open(sys.argv[2], "w") as o:
    o.write(next(i))
    for n, line in enumerate(i, 2):
        t = float(line.split(",")[0])
        if 6.5 < t < 8.5:
            continue  # 2 s without samples over the braking
        o.write(line)
        if n in (1001, 1501, 1601):
            o.write("%.3f,oops\n" % t)  # unreadable, after the row it copies
PY
run "$SW" forensics "$TMP/hole.csv" --scene "$LOGS/crate.ini" --no-what-if \
    --report "$TMP/hole.html" --json
expect_rc 0 "--report of a log with a hole"
cp "$TMP/out" "$TMP/hole.json"
render "$TMP/hole.html" "$TMP/hole-dom.html"
python3 - "$TMP/hole-dom.html" "$TMP/hole.json" <<'PY' || fail "the report of an incomplete verdict"
import json, sys
sys.path.insert(0, sys.argv[1].rsplit("/", 1)[0])
from page import Page, check_captions
p, j = Page(open(sys.argv[1]).read()), json.load(open(sys.argv[2]))
text = p.text
check_captions(p)
assert j["packages"][0]["verdict"] == "incomplete"
# at the top, before any answer, in words
at = text.find("The verdict is INCOMPLETE.")
assert 0 <= at < text.find("crate-A (2x0.728 m"), at
assert "a gap of 2 s at 6.500 s overlapped rocking" in text
assert "INCOMPLETE : upright as far as the samples go" in text or "INCOMPLETE: upright as far as the samples go" in text
# what was not used: the rows by reason with their lines, the gap
assert "3 of 18005 rows were refused" in text, text[text.find("rows were"):][:300]
assert "not a number 3 1002, 1503, 1604" in text, text[text.find("rows were"):][:400]
assert "gap 6.5000 2 " in text and "left incomplete: it overlapped motion" in text
assert p.ids.get("incomplete") == "div" and "rejected" in p.ids and "gaps" in p.ids
PY

# ---- lcm-logger files: the samples' utime, or lcm-logger's own clock ----
if [ -n "${SW_LCM_PYTHON_DIR:-}" ] && "$SW" --help | grep -q monitor; then
    # the samples stamped by a sensor with a set clock (2023-11-14T22:13:20Z)
    PYTHONPATH=$SW_LCM_PYTHON_DIR python3 "$SRC/docs/examples/csv2lcmlog.py" \
        "$LOGS/hard-stop-overturn.csv" "$TMP/drive.lcmlog" --start-utime 1700000000000000 >/dev/null
    run "$SW" forensics "$TMP/drive.lcmlog" --scene "$LOGS/crate.ini" --no-what-if \
        --report "$TMP/lcm.html" --json
    expect_rc 0 "--report of an lcm-logger file"
    cp "$TMP/out" "$TMP/lcm.json"
    render "$TMP/lcm.html" "$TMP/lcm-dom.html"
    python3 "$TMP/times.py" "$TMP/lcm-dom.html" "$TMP/lcm.json" 1700000000000000 ||
        fail "the UTC times of an lcm-logger file"
    grep -q "the samples' utime" "$TMP/lcm-dom.html" || fail "lcm-logger: where the dates come from"
    # a sensor that counts from its boot (utime 5 s at the start): the
    # times lcm-logger received the samples, 2 ms after they were taken
    PYTHONPATH=$SW_LCM_PYTHON_DIR python3 - "$LOGS/hard-stop-overturn.csv" "$TMP/boot.lcmlog" <<'PY'
import struct, sys
from swaywatch import accel_t
out = []
with open(sys.argv[1]) as f:
    next(f)
    for seq, line in enumerate(f):
        t, a = (float(x) for x in line.split(","))
        m = accel_t()
        m.utime, m.seq, m.ax = 5000000 + round(t * 1e6), seq, a
        data = m.encode()
        logged = 1716206400000000 + round(t * 1e6) + 2000
        out.append(struct.pack(">IqqII", 0xEDA1DA01, seq, logged, 5, len(data)) + b"ACCEL" + data)
open(sys.argv[2], "wb").write(b"".join(out))
PY
    run "$SW" forensics "$TMP/boot.lcmlog" --scene "$LOGS/crate.ini" --no-what-if \
        --report "$TMP/boot.html" --json
    expect_rc 0 "--report of an lcm-logger file of a sensor's boot time"
    cp "$TMP/out" "$TMP/boot.json"
    render "$TMP/boot.html" "$TMP/boot-dom.html"
    python3 "$TMP/times.py" "$TMP/boot-dom.html" "$TMP/boot.json" 1716206400002000 ||
        fail "the UTC times of an lcm-logger file from lcm-logger's clock"
    grep -q "lcm-logger's receive times" "$TMP/boot-dom.html" ||
        fail "lcm-logger's clock: where the dates come from"
fi

# A log with a lateral column and a crate with a depth that overturns
# across the truck (the shock along the truck, half as strong, leaves it
# upright): the answer, the moments and the close-up name the lateral
# plane, the figures draw its panel and say so in their captions, and the
# safety factor is the lateral plane's, named.
awk -F, 'NR == 1 { print "t_s,ax,ay"; next } { print $1 "," 0.5 * $2 "," $2 }' \
    "$LOGS/hard-stop-overturn.csv" >"$TMP/both.csv"
printf '[package]\nname = deep-crate\nheight = 2.0\nwidth = 1.2\ndepth = 0.728\nmass = 1000\n' \
    >"$TMP/deep.ini"
run "$SW" forensics "$TMP/both.csv" --scene "$TMP/deep.ini" --no-what-if \
    --report "$TMP/lat.html" --json
expect_rc 0 "--report with a lateral plane"
grep -q 'is not used' "$TMP/err" && fail "forensics did not use the lateral column"
cp "$TMP/out" "$TMP/lat.json"
render "$TMP/lat.html" "$TMP/lat-dom.html"
python3 - "$TMP/lat-dom.html" "$TMP/lat.json" <<'PY' || fail "the report of a lateral overturn"
import json, sys
sys.path.insert(0, sys.argv[1].rsplit("/", 1)[0])
from page import Page
p = Page(open(sys.argv[1]).read())
pk = json.load(open(sys.argv[2]))["packages"][0]
text = p.text
assert pk["plane"] == "lateral" and pk["overturned"], pk
sf = pk["safety_factor"]
assert sf["plane"] == "lateral" and sf["factor"] == sf["planes"]["lateral"]["factor"], sf
assert sf["planes"]["longitudinal"]["factor"] > 1 > sf["factor"], sf
assert "OVERTURNED across the truck at %.3f s" % pk["overturn_time"] in text, text[:600]
assert "it gave out across the truck" in text
assert "it gives out first across the truck" in text
assert sf["text"] in text
assert "overturned across the truck" in text  # the moments
figs = {f["id"]: f for f in p.figures}
for fid in ("figure", "zoom-0"):
    f = figs[fid]
    assert "tilt across the truck θ / α" in f["svg"], fid
    assert "θ/α across, deep-crate" in f["svg"], fid
    assert "the tilt across the truck of each package" in f["caption"], (fid, f["caption"][:300])
assert "the overturn of deep-crate across the truck at %.3f s" % pk["overturn_time"] in \
    figs["zoom-0"]["caption"], figs["zoom-0"]["caption"][:300]
PY
echo "ok"
