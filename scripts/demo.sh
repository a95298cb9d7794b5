#!/usr/bin/env bash
# Installs what is missing, builds, renders the bundled default scenario into out/default and
# draws out/default/preview.png (frames with their ground-truth boxes).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --plots
bash scripts/build.sh
./build/apps/ladarsim render assets/scenarios/default.json --out out/default
./build/apps/ladarsim preview out/default
# Algorithm 1 on the frames, scored against the ground truth. The default lambda comes from the
# dataset's sensor (1.2 line pitches, 180 here): with Algorithm 1's lambda = 7 the V-RBNN radius
# (2 cm at 600 m) is below the beam spacing of physically rendered frames (docs/detection.md).
./build/apps/ladarsim detect out/default --method vrbnn
./build/apps/ladarsim eval out/default --detections out/default/detections-vrbnn.json \
  --json out/default/eval-vrbnn.json --plot out/default/eval-vrbnn.png
