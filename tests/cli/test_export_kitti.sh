#!/usr/bin/env bash
# export-kitti end to end: a rendered scenario (a yawed "plane", a pitched and rolled "bird", an
# approaching drone, a drone out of reach, a building) exported and read back by an independent
# KITTI reader (check_kitti_export.py), with label boxes holding the objects' returns or, on
# request, ground truth's exact boxes; the default scenario and multi_target's labels hold their
# returns; bad input refused with one line and exit 2; a user's files never replaced.
# Usage: test_export_kitti.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
models="$(realpath "$src")/assets/models"

# The building model (20 x 12 x 15 m before size_m) gives boxes with three different extents, so
# that swapped dimensions or a wrong heading show.
cat >"$work/scenario.json" <<JSON
{
  "sensor": {"preset": "velodyne_vlp16", "position_m": [0, 0, 1]},
  "render": {"frames": 2, "seed": 3},
  "objects": [
    {"id": 1, "class": "building", "model": "$models/building.glb", "size_m": 6,
     "trajectory": {"type": "fixed", "position_m": [0, 25, 0]}},
    {"id": 2, "class": "plane", "model": "$models/building.glb", "size_m": 4,
     "trajectory": {"type": "fixed", "position_m": [12, 5, 0], "yaw_deg": 30}},
    {"id": 3, "class": "bird", "model": "$models/building.glb", "size_m": 3,
     "trajectory": {"type": "fixed", "position_m": [-10, -8, 1], "yaw_deg": -50, "pitch_deg": 15, "roll_deg": 10}},
    {"id": 4, "class": "drone", "model": "$models/quadcopter.glb", "size_m": 0.6,
     "trajectory": {"type": "approach", "start_m": [8, -6, 1.5], "towards_m": [0, 0, 1.5], "speed_mps": 2}},
    {"id": 5, "class": "drone", "model": "$models/quadcopter.glb", "size_m": 0.6,
     "trajectory": {"type": "fixed", "position_m": [-30, 40, 1]}}
  ]
}
JSON
"$bin" render "$work/scenario.json" --out "$work/d" --quiet >/dev/null || { echo "FAIL: the scenario did not render"; exit 1; }

"$bin" export-kitti "$work/d" --out "$work/k" >"$work/stdout" 2>"$work/stderr" || fail "export failed: $(cat "$work/stderr")"
grep -q "^exported 2 frames" "$work/stdout" || fail "no summary line: $(cat "$work/stdout")"
grep -q "^export, frame 2/2" "$work/stderr" || fail "no progress lines: $(cat "$work/stderr")"
/usr/bin/python3 "$src/tests/cli/check_kitti_export.py" "$work/d" "$work/k" || fail "the export does not read back as the dataset"
[ ! -e "$work/k.partial" ] && [ ! -e "$work/k.old" ] || fail "staging directories left behind"
"$bin" export-kitti "$work/d" --out "$work/exact" --exact-boxes >/dev/null 2>&1 || fail "export --exact-boxes failed"
/usr/bin/python3 "$src/tests/cli/check_kitti_export.py" "$work/d" "$work/exact" >"$work/stdout" ||
  fail "the export with exact boxes does not read back as the dataset: $(cat "$work/stdout")"

# A drone a kilometre away and a field of drones, birds and an aircraft (issue #33): every label
# holds its object's returns, which lie on beam axes up to half a footprint beside the object.
for scenario in default multi_target; do
  "$bin" render "$src/assets/scenarios/$scenario.json" --out "$work/$scenario" --frames 3 --quiet >/dev/null ||
    { fail "$scenario did not render"; continue; }
  "$bin" export-kitti "$work/$scenario" --out "$work/$scenario-kitti" >/dev/null 2>&1 || fail "export of $scenario failed"
  /usr/bin/python3 "$src/tests/cli/check_kitti_export.py" "$work/$scenario" "$work/$scenario-kitti" >"$work/stdout" ||
    fail "$scenario's export: $(cat "$work/stdout")"
done

# Exported again onto itself: the user's notes beside it are kept; a file of the user's inside
# training/ (camera images added later) is refused before anything is written.
echo "my notes" >"$work/k/NOTES.txt"
"$bin" export-kitti "$work/d" --out "$work/k" >"$work/stdout" 2>"$work/stderr" || fail "re-export failed: $(cat "$work/stderr")"
[ "$(cat "$work/k/NOTES.txt" 2>/dev/null)" = "my notes" ] || fail "NOTES.txt was lost in a re-export"
grep -q "NOTES.txt" "$work/stdout" || fail "the summary does not say NOTES.txt was kept: $(cat "$work/stdout")"
/usr/bin/python3 "$src/tests/cli/check_kitti_export.py" "$work/d" "$work/k" >/dev/null || fail "the re-export does not read back"

# Exit 2 and one line on stderr (besides progress lines) naming `word`.
expect_refusal() {
  local what=$1 word=$2 rc=$3
  [ "$rc" -eq 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(grep -cv "^intensity scan, frame \|^export, frame " "$work/stderr")" -eq 1 ] ||
    fail "$what: expected one line on stderr, got: $(cat "$work/stderr")"
  grep -q -- "$word" "$work/stderr" || fail "$what: the message does not say '$word': $(cat "$work/stderr")"
}

mkdir -p "$work/k/training/image_2" && echo png >"$work/k/training/image_2/000000.png"
before=$(ls -lR "$work/k" | md5sum)
"$bin" export-kitti "$work/d" --out "$work/k" >/dev/null 2>"$work/stderr"
expect_refusal "a user's image_2 inside training/" "training/image_2/" $?
[ "$before" = "$(ls -lR "$work/k" | md5sum)" ] || fail "the refused export directory was changed"

mkdir -p "$work/mine" && echo x >"$work/mine/thesis.tex"
"$bin" export-kitti "$work/d" --out "$work/mine" >/dev/null 2>"$work/stderr"
expect_refusal "--out onto a user's directory" "refusing to replace" $?
[ "$(ls "$work/mine")" = thesis.tex ] && [ ! -e "$work/mine.partial" ] || fail "the user's directory was touched"

"$bin" export-kitti "$work/nowhere" --out "$work/k2" >/dev/null 2>"$work/stderr"
expect_refusal "a missing dataset" "$work/nowhere: DIR: no such directory" $?
[ ! -e "$work/k2" ] || fail "a missing dataset left an export"

mkdir -p "$work/nomanifest/frames" && cp "$work/d/frames/000000.pcd" "$work/nomanifest/frames/"
"$bin" export-kitti "$work/nomanifest" --out "$work/k2" >/dev/null 2>"$work/stderr"
expect_refusal "a dataset without manifest.json" "nomanifest/manifest.json" $?

cp -r "$work/d" "$work/broken" && printf 'not a pcd\n' >"$work/broken/frames/000001.pcd"
"$bin" export-kitti "$work/broken" --out "$work/k2" >/dev/null 2>"$work/stderr"
expect_refusal "a malformed frame" "broken/frames/000001.pcd" $?
[ ! -e "$work/k2" ] || fail "a malformed frame left an export"

cp -r "$work/d" "$work/short" && /usr/bin/python3 - "$work/short/ground_truth.json" <<'PY'
import json, sys
truth = json.load(open(sys.argv[1]))
truth["frames"] = truth["frames"][:1]
json.dump(truth, open(sys.argv[1], "w"))
PY
"$bin" export-kitti "$work/short" --out "$work/k2" >/dev/null 2>"$work/stderr"
expect_refusal "ground truth without a frame" "ground_truth.json: frames: has no frame 1" $?
[ ! -e "$work/k2" ] && [ ! -e "$work/k2.partial" ] || fail "ground truth without a frame left an export"

if [ "$failures" -eq 0 ]; then echo "export-kitti: all checks passed"; else echo "export-kitti: $failures failed"; exit 1; fi
