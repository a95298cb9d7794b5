#!/usr/bin/env bash
# The viewer for a new user: the target's points show over the detection's outline; a VLP-16's
# 3600 x 16 range image is more than a one-pixel strip; a run without a cue (nor detections) has
# no target, rather than the background map (id 0) standing for one; an imported recording's panel
# counts frames as the slider does, gives time from its first frame, names its detections and says
# it has no range image.
# Usage: test_viewer_first_hour.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
py=/usr/bin/python3
servers=()
trap 'for s in "${servers[@]}"; do kill "$s" 2>/dev/null; done; rm -rf "$work"' EXIT
chrome=(chromium --headless=new --no-sandbox --disable-dev-shm-usage --disable-gpu --enable-unsafe-swiftshader --use-angle=swiftshader
        --virtual-time-budget=10000 --window-size=1280,720)

# serve DIR: starts `ladarsim view DIR` and sets $url.
serve() {
  "$bin" view "$1" --no-browser >"$1.view.log" 2>&1 &
  servers+=($!)
  for _ in $(seq 50); do grep -q http "$1.view.log" && break; sleep 0.1; done
  url=$(grep -o 'http://[^ ]*' "$1.view.log")
}
state_of() { "${chrome[@]}" --dump-dom "$1" 2>/dev/null | grep -o '<pre id="state">[^<]*' | sed 's/<pre id="state">//'; }

# The target under its detection: magenta pixels in the 3-D view.
"$bin" render "$src/tests/cli/small.json" --out "$work/run" --frames 3 --quiet >/dev/null || fail "render failed"
"$bin" detect "$work/run" --method vrbnn --lambda 180 >/dev/null 2>&1 || fail "detect failed"
serve "$work/run"
"${chrome[@]}" --screenshot="$work/view.png" "${url}?frame=1" >/dev/null 2>&1
$py - "$work/view.png" <<'PY' || fail "the target's points cannot be seen"
import sys
import matplotlib.image
image = matplotlib.image.imread(sys.argv[1])[:, :1280 - 320, :3]
r, g, b = image[..., 0], image[..., 1], image[..., 2]
magenta = int(((r > 0.85) & (g < 0.45) & (b > 0.85)).sum())
print(f"{magenta} target pixels")
sys.exit(0 if magenta >= 20 else 1)
PY

# A VLP-16 run: no cue, no detections; a 3600 x 16 range image.
"$bin" render "$src/assets/scenarios/vlp16_drone.json" --out "$work/vlp" --frames 2 --quiet >/dev/null || fail "VLP-16 render failed"
serve "$work/vlp"
state=$(state_of "${url}?frame=1")
node -e '
  const s = JSON.parse(process.argv[1]), problems = [];
  if (!s.ready) problems.push("not ready");
  if (s.target !== null) problems.push(`target ${JSON.stringify(s.target)} in a run without a cue or detections`);
  const r = s.range_image || {};
  if (r.width !== 3600 || r.height !== 16) problems.push(`range image ${r.width} x ${r.height}, expected 3600 x 16`);
  if (!(r.shown_height_px >= 48)) problems.push(`range image shown ${r.shown_height_px} px high`);
  if (problems.length) { console.log(problems.join("; ")); process.exit(1); }
' "$state" || fail "VLP-16 page state: $state"
"${chrome[@]}" --dump-dom "${url}?frame=1" 2>/dev/null | grep -q "none (no cue, no detections)" || fail "the panel does not say there is no target"

# A recorded capture, imported and detected: no object ids (so no target), no range images, times
# since 1970 and frames indexed from 0.
if [ ! -d "$shared_data/vlp16" ]; then skip "shared data not present: $shared_data"; else
  "$bin" import-velodyne "$shared_data/vlp16/velodyne_vlp16.pcap" --out "$work/recorded" >/dev/null || fail "import-velodyne failed"
  "$bin" detect "$work/recorded" --method vrbnn >/dev/null 2>&1 || fail "detect on the recording failed"
  serve "$work/recorded"
  "${chrome[@]}" --dump-dom "${url}?frame=0" 2>/dev/null >"$work/recorded.html"
  node -e '
    const dom = require("fs").readFileSync(process.argv[1], "utf8"), problems = [];
    const row = (name) => (dom.match(new RegExp(`<tr><td>${name}</td><td>([^<]*)</td></tr>`)) || [])[1];
    const label = (dom.match(/<span id="frame-label">([^<]*)</) || [])[1];
    const frame = row("frame"), slider = (label || "").split("/"), panel = (frame || "").split(" of ");
    if (!frame || panel[0] !== slider[0] || panel[1] !== slider[1])
      problems.push(`panel says frame "${frame}" beside the slider label "${label}"`);
    if (row("time") !== "0.000 s") problems.push(`time of the first frame "${row("time")}", expected "0.000 s"`);
    // detect finds a box in each frame of this capture (it says "2 detected"): the box is drawn.
    const target = row("target") || "";
    if (/no detections/.test(target) || !/drawn/.test(target)) problems.push(`target row "${target}" beside a drawn detection box`);
    if (!/<div id="range-box" hidden/.test(dom)) problems.push("the empty range-image box is shown");
    if (!/<p id="no-range">/.test(dom)) problems.push("nothing says recorded frames have no range image");
    if (problems.length) { console.log(problems.join("; ")); process.exit(1); }
  ' "$work/recorded.html" || fail "recorded dataset's page"
fi

finish "viewer first hour"
