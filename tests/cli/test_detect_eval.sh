#!/usr/bin/env bash
# detect and eval through the command line: detections record the dataset they were computed on,
# and eval refuses another dataset's.
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"
"$bin" render "$good" --out "$work/a" --quiet >/dev/null || fail "small scenario did not render"
"$bin" render "$good" --out "$work/b" --seed 8 --quiet >/dev/null || fail "small scenario did not render with seed 8"
# Plain detect: its defaults come from the dataset's sensor, and find the drone.
"$bin" detect "$work/a" >"$work/stdout" 2>&1 || fail "detect failed"
grep -q "over 3 frames: [1-3] detected" "$work/stdout" || fail "plain detect found nothing: $(cat "$work/stdout")"
"$bin" detect "$work/a" --radius -1 >/dev/null 2>&1
[ $? -ne 0 ] || fail "detect accepted --radius -1"
"$bin" detect "$work/a" --target-size 0.3 0 0.06 --out "$work/x.json" >/dev/null 2>&1
[ $? -ne 0 ] || fail "detect accepted a target size of 0"
"$bin" eval "$work/a" --detections "$work/a/detections-vrbnn.json" --json "$work/scores.json" >/dev/null 2>&1 ||
  fail "eval of its own dataset failed"
# The scores of both boxes, in 3-D and in bird's-eye view, each within [0, 1].
python3 - "$work/scores.json" <<'PY' || fail "eval --json lacks a score: $(head -c 400 "$work/scores.json")"
import json, sys
s = json.load(open(sys.argv[1]))
for scores in (s, s["point_box"]):
    for key in ("mean_iou", "mean_iou_bev"):
        assert 0.0 <= scores[key] <= 1.0, key
assert s["mean_l2_m"] is not None and all("iou_bev" in f and "points_iou" in f for f in s["per_frame"])
# Every target: CLEAR MOT and centre-distance AP, and the counts they come from.
t = s["tracking"]
assert t["matches"] + t["misses"] == t["objects"] > 0
assert abs(s["mota"] - (1 - (t["misses"] + t["false_positives"] + s["id_switches"]) / t["objects"])) < 1e-9
assert s["motp_m"] >= 0 and 0 <= s["ap_centre"] <= 1 and 0 <= s["ap_centre_3d"] <= 1 and "drone" in t["per_class"]
PY
"$bin" eval "$work/b" --detections "$work/a/detections-vrbnn.json" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "eval with another dataset's detections exited $rc, expected 2"
grep -q "$work/a" "$work/stderr" && grep -q "not of $work/b" "$work/stderr" ||
  fail "the refusal does not name both datasets: $(cat "$work/stderr")"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "the refusal is not one line: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "detect/eval: all checks passed"; else echo "detect/eval: $failures failed"; exit 1; fi
