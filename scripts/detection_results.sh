#!/usr/bin/env bash
# docs/detection.md's results tables: renders the scenarios (if not rendered yet), runs every
# detector configuration on them with `ladarsim benchmark` (which runs the detector itself and
# scores it, EAO included) and prints mean L2, IoU and EAO (in 3-D and bird's-eye view, of the
# sensor-aware box and of the box around the points) and every target's MOTA and AP as a markdown
# table, header included. tests/cli/test_detection_table.sh checks the committed small table
# against a fresh run of this script.
# Usage: scripts/detection_results.sh [--frames N] [--root OUT_ROOT] [SCENARIO ...]
#   default: every frame of the four datasets (and their Autzen variants where
#   ../shared/data/autzen is present) rendered under out/; --frames N renders N frames of each,
#   under OUT_ROOT/SCENARIO-Nf. LADARSIM_BIN names the binary (default build/apps/ladarsim).
set -euo pipefail
cd "$(dirname "$0")/.."
root=out
frames=
names=()
while [ $# -gt 0 ]; do
  case $1 in
    --frames) frames=$2; shift 2 ;;
    --root) root=$2; shift 2 ;;
    *) names+=("$1"); shift ;;
  esac
done
if [ ${#names[@]} -eq 0 ]; then
  names=(dataset1 dataset2 dataset3 dataset4)
  [ -f ../shared/data/autzen/autzen_trim.pcd ] && names+=(dataset1-autzen dataset2-autzen dataset3-autzen dataset4-autzen)
fi
bin=${LADARSIM_BIN:-./build/apps/ladarsim}
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
  label=${n#dataset}
  if [ -n "$frames" ]; then
    dir=$root/$n-${frames}f
    label="$label, $frames frames"
    [ -f "$dir/manifest.json" ] || $bin render "assets/scenarios/$n.json" --out "$dir" --frames "$frames" --quiet >/dev/null
  else
    dir=$root/$n
    [ -f "$dir/manifest.json" ] || $bin render "assets/scenarios/$n.json" --out "$dir" --quiet >/dev/null
  fi
  for config in "${configs[@]}"; do
    name=${config%%|*}
    # shellcheck disable=SC2086
    $bin benchmark "$dir" ${config#*|} --json "$dir/eval-$name.json" >/dev/null
    /usr/bin/python3 - "$dir/eval-$name.json" "$label" "$name" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
f = lambda v: '-' if v is None else '%.3f' % v
p = e['point_box']
print('| %s | %s | %s | %.3f | %.3f | %.3f | %.3f | %.3f / %.3f / %.3f | %d | %d | %s / %s |' % (
    sys.argv[2], sys.argv[3], f(e['mean_l2_m']), e['mean_iou'], e['mean_iou_bev'], e['eao'], e['eao_bev'],
    p['mean_iou'], p['mean_iou_bev'], p['eao_bev'], e['failures'], e['frames_lost'], f(e['mota']), f(e['ap_centre'])))
PY
  done
done
