#!/usr/bin/env bash
# One rule for background.pcd: every rendered dataset has one, the static scene in view, with 0
# points when there is nothing static; detect subtracts nothing then and says why without a
# warning. Only a recorded (imported) dataset has none, and detect warns about that.
# Usage: test_background_rule.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

points_of() { grep -a "^POINTS " "$1" | cut -d' ' -f2; }

# Nothing static: a drone alone.
cat >"$work/drone_only.json" <<JSON
{
  "sensor": {"position_m": [0, 0, 2], "cue_object": 2},
  "render": {"frames": 2, "seed": 7, "footprint_samples": 9},
  "objects": [
    {"id": 2, "class": "drone", "model": "$src/assets/models/quadcopter.glb",
     "trajectory": {"type": "approach", "start_m": [120, 1, 4], "towards_m": [0, 0, 4], "speed_mps": 15}}
  ]
}
JSON
"$bin" render "$work/drone_only.json" --out "$work/none" --quiet >"$work/stdout" 2>&1 || fail "render failed: $(cat "$work/stdout")"
[ -f "$work/none/background.pcd" ] || fail "a scenario with nothing static wrote no background.pcd"
[ "$(points_of "$work/none/background.pcd")" = 0 ] || fail "background.pcd of nothing static has $(points_of "$work/none/background.pcd") points"
grep -q "background.pcd (0 points" "$work/stdout" || fail "the summary does not name the 0-point background.pcd: $(cat "$work/stdout")"
"$bin" detect "$work/none" >"$work/stdout" 2>"$work/stderr" || fail "detect failed: $(cat "$work/stderr")"
grep -q "warning" "$work/stderr" && fail "detect warns on a 0-point background.pcd: $(cat "$work/stderr")"
grep -q "no background.pcd" "$work/stderr" && fail "detect says there is no background.pcd when there is one: $(cat "$work/stderr")"
grep -q "background.pcd has 0 points" "$work/stderr" || fail "detect does not say the background is empty: $(cat "$work/stderr")"

# Something static: a map with points, and detect quiet about it.
"$bin" render "$src/tests/cli/small.json" --out "$work/some" --quiet >/dev/null 2>&1 || fail "small render failed"
[ "$(points_of "$work/some/background.pcd")" -gt 0 ] || fail "background.pcd of a building is empty"
"$bin" detect "$work/some" >/dev/null 2>"$work/stderr" || fail "detect failed"
grep -q "background" "$work/stderr" && fail "detect talks about a good background.pcd: $(cat "$work/stderr")"

# A recorded dataset has none: detect warns.
pcap="$shared_data/vlp16/velodyne_vlp16.pcap"
if [ -f "$pcap" ]; then
  "$bin" import-velodyne "$pcap" --out "$work/rec" >/dev/null 2>&1 || fail "import failed"
  [ ! -e "$work/rec/background.pcd" ] || fail "a recorded dataset has a background.pcd"
  "$bin" detect "$work/rec" >/dev/null 2>"$work/stderr"
  grep -q "no background.pcd" "$work/stderr" || fail "detect does not warn about a recorded dataset without a map: $(cat "$work/stderr")"
else
  skip "$pcap absent, a recorded dataset's missing map not checked"
fi

finish "background rule"
