#!/usr/bin/env bash
# The HTML report in a real browser: headless Chromium (Debian's `chromium`, installed here if missing) opens a
# report written by `quadcover render --report-html` from disk, offline. Checks: the page's status says "ok" (no
# script error), Chromium logs no console error, every 3D canvas has drawn pixels (the viewer counts non-background
# pixels with readPixels), and a screenshot of the page shows the rendered mesh.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${BUILD_DIR:-build}
QC="$BUILD/quadcover"
[ -x "$QC" ] || { echo "40_html: $QC not built"; exit 1; }
if ! command -v chromium >/dev/null 2>&1; then
  echo "40_html: installing chromium"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends chromium >/dev/null
fi
PY=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A parameterized torus (per-corner vt, seams where the angles wrap) and a quad mesh.
"$PY" - "$work" <<'PYEOF'
import math, sys
out = sys.argv[1]
nM, nm, R, r = 32, 16, 2.0, 0.7
vid = lambda i, j: (i % nM) * nm + (j % nm) + 1
pos = []
for i in range(nM):
    for j in range(nm):
        u, v = 2 * math.pi * i / nM, 2 * math.pi * j / nm
        pos.append("v %.6f %.6f %.6f" % ((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u), r * math.sin(v)))
tri, quad, vts = [], [], []
for i in range(nM):
    for j in range(nm):
        c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
        quad.append("f " + " ".join(str(vid(a, b)) for a, b in c))
        for t in ([0, 1, 2], [0, 2, 3]):
            corners = []
            for k in t:
                a, b = c[k]
                vts.append("vt %.4f %.4f" % (a / 4.0, b / 4.0))
                corners.append("%d/%d" % (vid(a, b), len(vts)))
            tri.append("f " + " ".join(corners))
open(out + "/torus_param.obj", "w").write("\n".join(pos + vts + tri) + "\n")
open(out + "/torus_quads.obj", "w").write("\n".join(pos + quad) + "\n")
open(out + "/report.json", "w").write('{"faces": %d, "E_D": 0.5, "seamless": true, "optimize": {"log": [{"evaluation": 0, "E_D": 1.0, "branch_points": 4}, {"evaluation": 1, "E_D": 0.5, "branch_points": 6}]}}' % len(tri))
PYEOF

"$QC" render "$work/torus_param.obj" --report-html "$work/report.html" --metrics "$work/report.json" \
  --quads "$work/torus_quads.obj" -q
FLAGS=(--headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --disable-extensions
       --enable-logging=stderr --log-level=0 --virtual-time-budget=20000)
timeout 120 chromium "${FLAGS[@]}" --dump-dom "file://$work/report.html" >"$work/dom.html" 2>"$work/console.txt" || true
timeout 120 chromium "${FLAGS[@]}" --window-size=1200,1000 --screenshot="$work/shot.png" "file://$work/report.html" \
  >/dev/null 2>>"$work/console.txt" || true

"$PY" - "$work" <<'PYEOF'
import re, struct, sys, zlib
work = sys.argv[1]
dom = open(work + "/dom.html", encoding="utf-8").read()
ok = True
def check(cond, msg):
    global ok
    print(("ok    " if cond else "FAIL  ") + msg)
    ok = ok and cond
status = re.search(r'id="qc-status" data-state="(\w+)">([^<]*)', dom)
check(status is not None and status.group(1) == "ok", "page status: %s" % (status.group(2) if status else "missing"))
counts = [int(n) for n in re.findall(r'data-nonblank="(\d+)"', dom)]
check(len(counts) == 2 and min(counts) > 5000, "both 3D canvases drew pixels: %s" % counts)
errors = [l for l in open(work + "/console.txt", errors="replace") if ":CONSOLE" in l and
          re.search(r"Uncaught|Error|error|Failed", l) and "GL Driver Message" not in l]
check(not errors, "no console errors" + ("".join("\n      " + e.strip() for e in errors[:5])))

# Decode the screenshot (8-bit RGB/RGBA PNG) and count non-white pixels where the first canvas sits.
data = open(work + "/shot.png", "rb").read()
check(data[:8] == b"\x89PNG\r\n\x1a\n", "screenshot is a PNG")
pos, idat, w = 8, b"", 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8]); body = data[pos + 8:pos + 8 + n]; pos += 12 + n
    if kind == b"IHDR": w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
    elif kind == b"IDAT": idat += body
bpp = 4 if ctype == 6 else 3
raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0; b = prev[i]; c = prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line); prev = line
colours = set()
for y in range(0, h, 4):
    for x in range(0, w, 4):
        colours.add(tuple(rows[y][x * bpp:x * bpp + 3]))
check(len(colours) > 50, "screenshot shows shaded content (%d distinct colours)" % len(colours))
sys.exit(0 if ok else 1)
PYEOF
