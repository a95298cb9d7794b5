#!/usr/bin/env bash
# Renders the paper's four datasets (if not rendered yet), runs every detector configuration on
# them and prints mean L2, IoU and EAO (in 3-D and bird's-eye view, of the sensor-aware box and of
# the box around the points) as a markdown table (docs/detection.md).
# Usage: scripts/detection_results.sh [OUT_ROOT] [SCENARIO ...]   (default out/; the four
# datasets, and their Autzen variants where ../shared/data/autzen is present)
set -euo pipefail
cd "$(dirname "$0")/.."
root=${1:-out}
shift || true
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  names=(dataset1 dataset2 dataset3 dataset4)
  [ -f ../shared/data/autzen/autzen_trim.pcd ] && names+=(dataset1-autzen dataset2-autzen dataset3-autzen dataset4-autzen)
fi
bin=./build/apps/ladarsim
configs=(
  "rbnn-0.06|--method rbnn --radius 0.06"
  "rbnn-0.2|--method rbnn --radius 0.2"
  "vrbnn-paper|--method vrbnn --lambda 7"
  "vrbnn|--method vrbnn --lambda 180"
  "kalman|--method kalman --lambda 180"
)
echo "| dataset | detector | mean L2 (m) | mean IoU | IoU, bird's-eye | EAO | EAO, bird's-eye | points' box: IoU / bird's-eye / EAO bird's-eye | failures | frames lost | every target: MOTA / AP |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for n in "${names[@]}"; do
  dir=$root/$n
  [ -f "$dir/manifest.json" ] || $bin render "assets/scenarios/$n.json" --out "$dir" --quiet >/dev/null
  for config in "${configs[@]}"; do
    name=${config%%|*}
    # shellcheck disable=SC2086
    $bin detect "$dir" ${config#*|} --out "$dir/detections-$name.json" >/dev/null
    $bin eval "$dir" --detections "$dir/detections-$name.json" --json "$dir/eval-$name.json" >/dev/null
    /usr/bin/python3 -c "
import json, sys
e = json.load(open('$dir/eval-$name.json'))
l2 = '-' if e['mean_l2_m'] is None else '%.3f' % e['mean_l2_m']
p = e['point_box']
f = lambda v: '-' if v is None else '%.3f' % v
print('| ${n#dataset} | $name | %s | %.3f | %.3f | %.3f | %.3f | %.3f / %.3f / %.3f | %d | %d | %s / %s |' % (
    l2, e['mean_iou'], e['mean_iou_bev'], e['eao'], e['eao_bev'], p['mean_iou'], p['mean_iou_bev'], p['eao_bev'],
    e['failures'], e['frames_lost'], f(e['mota']), f(e['ap_centre'])))"
  done
done
