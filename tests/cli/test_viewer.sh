#!/usr/bin/env bash
# `ladarsim view` in a real browser: headless Chromium loads the page for a small rendered run;
# the page's own state must match the files (points of the frame, boxes of its ground truth and
# detections), and its screenshot must show more than background. The server answers on the
# loopback interface only and never outside the run directory.
# Usage: test_viewer.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

"$bin" render "$src/tests/cli/small.json" --out "$work/run" --frames 3 --quiet >/dev/null || fail "render failed"
"$bin" detect "$work/run" --method vrbnn --lambda 180 >/dev/null 2>&1 || fail "detect failed"
"$bin" view "$work/run" --no-browser >"$work/view.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 50); do grep -q http "$work/view.log" && break; sleep 0.1; done
url=$(grep -o 'http://[^ ]*' "$work/view.log")
port=${url##*:}
port=${port%/}
[ -n "$port" ] || { fail "no URL printed: $(cat "$work/view.log")"; exit 1; }

# Loopback only: the listening socket is bound to 127.0.0.1 (0100007F in /proc/net/tcp).
printf -v hex_port '%04X' "$port"
grep -q " 0100007F:$hex_port 00000000:0000 0A" /proc/net/tcp || fail "the server does not listen on 127.0.0.1:$port alone"

# Requests for files outside the run directory are refused.
get_status() {
  exec 3<>"/dev/tcp/127.0.0.1/$port"
  printf 'GET %s HTTP/1.0\r\n\r\n' "$1" >&3
  head -1 <&3 | tr -d '\r'
  exec 3<&-
}
for path in /run/../../etc/passwd /run/%2e%2e/%2e%2e/etc/passwd /run//etc/passwd /viewer/../../CMakeLists.txt /run/.hidden; do
  status=$(get_status "$path")
  [[ $status == *" 200 "* || $status == *" 200" ]] && fail "served $path outside the run directory: $status"
done
[[ $(get_status /run/manifest.json) == *" 200"* ]] || fail "the manifest is not served"

# The page in a browser: its state against the files of frame 1.
chrome=(chromium --headless=new --no-sandbox --disable-dev-shm-usage --disable-gpu --enable-unsafe-swiftshader --use-angle=swiftshader
        --virtual-time-budget=10000 --window-size=1280,720)
"${chrome[@]}" --dump-dom "${url}?frame=1" 2>/dev/null >"$work/dom.html"
state=$(grep -o '<pre id="state">[^<]*' "$work/dom.html" | sed 's/<pre id="state">//')
[ -n "$state" ] || { fail "the page reported no state"; exit 1; }
points=$(grep -a -m1 '^POINTS' "$work/run/frames/000001.pcd" | cut -d' ' -f2)
node -e '
  const [state, points, truthFile, detectionsFile] = process.argv.slice(1);
  const s = JSON.parse(state), truth = require(truthFile), det = require(detectionsFile);
  const background = new Set(["background", "terrain", "building", "tree"]);
  const boxes = truth.frames[1].objects.filter((o) => !background.has(o.class)).length;
  const detected = det.detections[1].found ? 1 : 0;
  const problems = [];
  if (!s.ready) problems.push("not ready: " + state);
  if (s.points !== Number(points)) problems.push(`points ${s.points} != ${points} in the PCD`);
  if (s.boxes !== boxes) problems.push(`ground-truth boxes ${s.boxes} != ${boxes}`);
  if (s.detected_boxes !== detected) problems.push(`detected boxes ${s.detected_boxes} != ${detected}`);
  const targetReturns = truth.frames[1].objects.find((o) => o.id === det.target).returns;
  if (s.target_returns !== targetReturns) problems.push(`target returns ${s.target_returns} != ${targetReturns}`);
  if (problems.length) { console.log(problems.join("; ")); process.exit(1); }
' "$state" "$points" "$work/run/ground_truth.json" "$work/run/detections-vrbnn.json" || fail "page state: $state"

# A screenshot with something drawn on it besides the background.
"${chrome[@]}" --screenshot="$work/view.png" "${url}?frame=1" >/dev/null 2>&1
python3 - "$work/view.png" <<'PY' || fail "the screenshot shows nothing but background"
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n"
pos, idat, width, height = 8, b"", 0, 0
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    if kind == b"IHDR":
        width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        channels = {2: 3, 6: 4}[colour]
    elif kind == b"IDAT":
        idat += body
    pos += 12 + length
raw, stride, rows, prev = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
for y in range(height):
    kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - channels] if i >= channels else 0
        b, c = prev[i], prev[i - channels] if i >= channels else 0
        p = a + b - c
        predictor = [0, a, b, (a + b) // 2, a if abs(p - a) <= min(abs(p - b), abs(p - c)) else (b if abs(p - b) <= abs(p - c) else c)][kind]
        line[i] = (line[i] + predictor) & 0xFF
    rows.append(line)
    prev = line
# The 3-D view is the left part of the page; its background is #111111.
scene_width = width - 320
lit = sum(1 for line in rows for x in range(scene_width)
          if max(abs(line[x * channels + k] - 0x11) for k in range(3)) > 40)
print(f"{lit} drawn pixels in the 3-D view")
sys.exit(0 if lit > 200 else 1)
PY

if [ "$failures" -eq 0 ]; then echo "viewer: all checks passed"; else echo "viewer: $failures failed"; exit 1; fi
