#!/bin/sh
# Renders RUNDIR/index.html in headless Chromium and checks that
# - the screenshot is not blank: more than 2 % of its pixels differ from white;
# - the page never scrolls sideways, at a desktop (1200 px) and a phone (480 px) window width:
#   the document's scrollWidth is at most its clientWidth, measured by a script in a copy of
#   the page (a <base> pointing at RUNDIR, so the pictures load) after every picture loaded
#   (--dump-dom prints the DOM the script wrote its figures into).
# Exit 77 (CTest: skipped) when chromium is absent.
# Usage: render_report.sh RUNDIR WORKDIR
run=$1; work=$2
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "SKIPPED: chromium is not installed (bash .ci/setup installs Debian's chromium)"; exit 77
fi
rm -rf "$work"; mkdir -p "$work/profile"
rundir=$(cd "$run" && pwd)
chrome() {
  "$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$work/profile" "$@" 2>>"$work/chromium.log"
}
chrome --window-size=1200,1600 --screenshot="$work/report.png" "file://$rundir/index.html" >/dev/null
test -s "$work/report.png" || { echo "no screenshot"; cat "$work/chromium.log"; exit 1; }
python3 - "$rundir/index.html" "$work/measure.html" "file://$rundir/" <<'PY'
import sys
page = open(sys.argv[1], encoding="utf-8").read()
probe = ("<script>window.addEventListener('load', function () {"
         "var d = document.documentElement;"
         "document.body.setAttribute('data-widths', d.scrollWidth + ' ' + d.clientWidth);"
         "});</script>")
page = page.replace("<head>", '<head><base href="' + sys.argv[3] + '">', 1)
page = page.replace("</body>", probe + "</body>", 1)
open(sys.argv[2], "w", encoding="utf-8").write(page)
PY
fail=0
for width in 1200 480; do
  chrome --window-size=$width,1600 --virtual-time-budget=10000 --dump-dom "file://$work/measure.html" \
    >"$work/dom_$width.html"
  widths=$(sed -n 's/.*data-widths="\([0-9]*\) \([0-9]*\)".*/\1 \2/p' "$work/dom_$width.html" | head -1)
  if [ -z "$widths" ]; then echo "window $width px: the page did not report its width"; fail=1; continue; fi
  set -- $widths
  echo "window $width px: page scroll width $1 px, visible width $2 px"
  [ "$1" -le "$2" ] || { echo "the page scrolls sideways at $width px"; fail=1; }
done
python3 - "$work/report.png" <<'PY' || fail=1
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, w, h, ctype = 8, b"", 0, 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR": w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
    if kind == b"IDAT": idat += body
    pos += 12 + n
bpp = {2: 3, 6: 4}[ctype]
raw, stride = zlib.decompress(idat), w * bpp
prev, nonwhite, i = bytearray(stride), 0, 0
for y in range(h):
    f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride]); i += 1 + stride
    for x in range(stride):
        a = line[x - bpp] if x >= bpp else 0
        b, c = prev[x], prev[x - bpp] if x >= bpp else 0
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    nonwhite += sum(1 for x in range(0, stride, bpp) if min(line[x:x + 3]) < 240)
    prev = line
share = nonwhite / (w * h)
print(f"screenshot {w}x{h}: {100 * share:.1f} % of pixels not white")
sys.exit(0 if share > 0.02 and w == 1200 else 1)
PY
exit $fail
