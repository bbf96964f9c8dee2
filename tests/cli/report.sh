# SPDX-License-Identifier: GPL-3.0-or-later
# report.sh - "swaywatch forensics --report FILE.html": one self-contained
# page, checked as a browser renders it.  Headless Chromium loads it with
# the network cut off and scripts disabled, logs no console error, and
# the rendered DOM holds the answer, the log's facts, the figure, the
# events, the what-if table, the limits and the command; its screenshot
# is not blank.  Skipped (77) where Chromium is not installed.
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
# shellcheck disable=SC2086
timeout 120 "$CHROME" $FLAGS --enable-logging=stderr --v=0 --dump-dom \
    "file://$TMP/incident.html" >"$TMP/dom.html" 2>"$TMP/chrome.err" ||
    { cat "$TMP/chrome.err" >&2; fail "chromium could not render the report"; }
grep -i 'CONSOLE' "$TMP/chrome.err" && fail "console messages while rendering the report"
# shellcheck disable=SC2086
timeout 120 "$CHROME" $FLAGS --window-size=1200,2400 --screenshot="$TMP/shot.png" \
    "file://$TMP/incident.html" >/dev/null 2>"$TMP/chrome2.err" ||
    { cat "$TMP/chrome2.err" >&2; fail "chromium could not take a screenshot"; }

python3 - "$TMP/dom.html" "$TMP/f.json" "$TMP/shot.png" <<'PY' || fail "the rendered report"
import html.parser, json, struct, sys, zlib

dom, facts, shot = open(sys.argv[1]).read(), json.load(open(sys.argv[2])), sys.argv[3]

class Text(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.text, self.ids, self.svg, self.skip = [], set(), 0, 0
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "svg":
            self.svg += 1
        if tag in ("style", "title"):
            self.skip += 1
    def handle_endtag(self, tag):
        if tag in ("style", "title"):
            self.skip -= 1
    def handle_data(self, d):
        if not self.skip:
            self.text.append(d)

p = Text()
p.feed(dom)
text = " ".join(" ".join(p.text).split())
want = ["Incident report", "crate-A", "crate-A-on-frame", "OVERTURNED", "Safety factor [",
        "It overturned", "The recording", "sample rate", "1000 Hz", "peak |bed acceleration|",
        "gaps", "Events", "uplift", "overturn", "What would have saved it", "as given",
        "frame, soft bearings", "cushion, firm", "Assumptions and limits", "swaywatch forensics",
        "hard-stop-overturn.csv", "--report", "Smallest reserve"]
missing = [w for w in want if w not in text]
assert not missing, missing
assert {"answer-0", "answer-1", "log", "figure", "events"} <= p.ids, p.ids
assert p.svg >= 1, "no figure"
assert "reserve (g)" in dom, "no reserve panel in the figure"
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
echo "ok"
