#!/usr/bin/env bash
# The viewer for a new user: the target's points show over the detection's outline; a VLP-16's
# 3600 x 16 range image is more than a one-pixel strip; a run without a cue (nor detections) has
# no target, rather than the background map (id 0) standing for one.
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

if [ "$failures" -eq 0 ]; then echo "viewer first hour: all checks passed"; else echo "viewer first hour: $failures failed"; exit 1; fi
