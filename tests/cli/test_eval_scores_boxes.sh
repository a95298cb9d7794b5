#!/usr/bin/env bash
# eval scores the boxes of a detections file and nothing else (issue #33's hand-made files): a
# file that detects nothing scores nothing whatever it claims, a perfect file scores as perfect
# whatever run's numbers it carries, malformed claims are refused naming the field, frames are
# matched by their `frame` field (a reversed file scores as the ordered one; a missing or repeated
# frame is named), and EAO, which needs the tracker in the loop, comes from `benchmark` alone.
# Usage: test_eval_scores_boxes.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
py=/usr/bin/python3
"$bin" render "$src/tests/cli/small.json" --out "$work/a" --quiet >/dev/null || fail "small scenario did not render"
"$bin" detect "$work/a" --lambda 180 --out "$work/detect.json" >/dev/null 2>&1 || fail "detect failed"

# The hand-made files, from detect's own report: its dataset, target and tracks kept.
$py - "$work" <<'PY' || fail "could not write the hand-made files"
import copy, json, sys
work = sys.argv[1]
report = json.load(open(f"{work}/detect.json"))
truth = json.load(open(f"{work}/a/ground_truth.json"))
target = report["target"]

def enclosing_box(box):
    """The axis-aligned box enclosing an oriented box, as eval's ground truth is."""
    w, x, y, z = box["orientation_wxyz"]
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    half = [sum(abs(r[i][j]) * box["size_m"][j] / 2 for j in range(3)) for i in range(3)]
    return {"centre_m": box["centre_m"], "size_m": [2 * h for h in half]}

def detection(frame, box):
    d = {"frame": frame, "time_s": 0.0, "found": box is not None, "predicted": False, "points": 0, "radius_m": 0.2}
    box = box or {"centre_m": [0, 0, 0], "size_m": [0, 0, 0]}
    d.update(box)
    d["sensor_box"] = box
    return d

def block(iou, failures):
    n = len(report["detections"])
    run = {"iou": [iou] * n, "initialised": [k == 0 for k in range(n)], "failures": failures}
    return {name: copy.deepcopy(run) for name in ("points_3d", "points_bev", "sensor_3d", "sensor_bev")}

def write(name, detections, supervised=None):
    out = {k: v for k, v in report.items() if k != "supervised"}
    out["detections"] = detections
    if supervised is not None: out["supervised"] = supervised
    json.dump(out, open(f"{work}/{name}.json", "w"))

frames = [f["index"] for f in truth["frames"]]
perfect = [detection(f["index"], enclosing_box(next(o for o in f["objects"] if o["id"] == target)["box_sensor"]))
           for f in truth["frames"]]
write("nothing-claims-one", [detection(f, None) for f in frames], block(1.0, 0))
write("perfect-other-block", perfect, block(0.478, 2))
bad = block(1.0, 0)
bad["sensor_3d"]["iou"][1] = 5.0
write("iou-five", perfect, bad)
write("no-block", perfect)
reversed_report = copy.deepcopy(report)
reversed_report["detections"].reverse()
reversed_report["tracks"].reverse()
json.dump(reversed_report, open(f"{work}/reversed.json", "w"))
write("missing-frame", [d for d in perfect if d["frame"] != frames[1]])
write("repeated-frame", [perfect[0], perfect[0]] + perfect[2:])
negative = copy.deepcopy(perfect)
negative[2]["size_m"] = [0.3, -0.3, 0.06]
write("negative-size", negative)
PY

# scores FILE: eval's JSON of a hand-made file, exit status in $rc, stderr in $work/stderr.
scores() {
  "$bin" eval "$work/a" --detections "$work/$1.json" --json "$work/$1-scores.json" >"$work/$1-stdout" 2>"$work/stderr"
  rc=$?
}
check() {  # check NAME PYTHON-ASSERTIONS: on the scores of NAME (s)
  $py - "$work/$1-scores.json" "$2" <<'PY' || fail "$1: $(head -c 600 "$work/$1-scores.json")"
import json, sys
s = json.load(open(sys.argv[1]))
exec(sys.argv[2])
PY
}

scores nothing-claims-one
[ "$rc" -eq 0 ] || fail "a file that detects nothing was refused ($rc): $(cat "$work/stderr")"
check nothing-claims-one 'assert s["mean_iou"] == 0 and s["frames_lost"] == s["frames"] == 3 and s["mean_l2_m"] is None
assert "eao" not in s and "eao" not in s["point_box"], "EAO taken from the file"'

scores perfect-other-block
[ "$rc" -eq 0 ] || fail "a perfect file was refused ($rc): $(cat "$work/stderr")"
check perfect-other-block 'assert s["mean_iou"] > 0.999 and s["mean_iou_bev"] > 0.999 and s["mean_l2_m"] < 1e-6, s
assert s["frames_lost"] == 0 and "eao" not in s and "failures" not in s, "scores taken from the file"'

scores iou-five
[ "$rc" -eq 2 ] || fail "a supervised block claiming IoU 5.0 exited $rc, expected 2"
grep -q "supervised.sensor_3d.iou\[1\]" "$work/stderr" || fail "IoU 5.0 refused without naming its field: $(cat "$work/stderr")"

scores no-block
[ "$rc" -eq 0 ] || fail "a file without a supervised block was refused ($rc): $(cat "$work/stderr")"
check no-block 'assert s["mean_iou"] > 0.999
assert {"average_overlap", "l2", "mot", "ap"} <= set(s["measures"]), s["measures"]'
grep -q "supports" "$work/no-block-stdout" || fail "eval does not say which measures the file supports: $(cat "$work/no-block-stdout")"

"$bin" eval "$work/a" --detections "$work/detect.json" --json "$work/ordered-scores.json" >/dev/null 2>&1 || fail "eval of detect's file failed"
scores reversed
[ "$rc" -eq 0 ] || fail "a reversed file was refused ($rc): $(cat "$work/stderr")"
$py - "$work/ordered-scores.json" "$work/reversed-scores.json" <<'PY' || fail "a reversed file does not score as the ordered one"
import json, sys
ordered, reversed_ = (json.load(open(f)) for f in sys.argv[1:])
for key in ("mean_l2_m", "mean_iou", "mean_iou_bev", "frames_lost", "mota", "motp_m", "ap_centre", "per_frame"):
    if ordered[key] != reversed_[key]: sys.exit(f"{key}: {ordered[key]} ordered, {reversed_[key]} reversed")
PY

frame1=$($py -c "import json, sys; print(json.load(open(sys.argv[1]))['frames'][1]['index'])" "$work/a/ground_truth.json")
frame0=$($py -c "import json, sys; print(json.load(open(sys.argv[1]))['frames'][0]['index'])" "$work/a/ground_truth.json")
scores missing-frame
[ "$rc" -eq 2 ] || fail "a file missing a frame exited $rc, expected 2"
grep -q "no detection for frame $frame1\b" "$work/stderr" || fail "the missing frame is not named: $(cat "$work/stderr")"
scores repeated-frame
[ "$rc" -eq 2 ] || fail "a file with a frame twice exited $rc, expected 2"
grep -q "frame $frame0 .*twice" "$work/stderr" || fail "the repeated frame is not named: $(cat "$work/stderr")"
scores negative-size
[ "$rc" -eq 2 ] || fail "a box of negative size exited $rc, expected 2"
grep -q "detections\[2\].size_m" "$work/stderr" || fail "the negative size is not named: $(cat "$work/stderr")"

# EAO runs the detector itself, the tracker in the loop.
"$bin" benchmark "$work/a" --method vrbnn --lambda 180 --json "$work/benchmark-scores.json" >"$work/stdout" 2>&1 ||
  fail "benchmark failed: $(cat "$work/stdout")"
check benchmark 'assert 0 <= s["eao"] <= 1 and 0 <= s["eao_bev"] <= 1 and 0 <= s["point_box"]["eao"] <= 1 and s["failures"] >= 0
assert "eao" in s["measures"] and all("supervised_iou" in f for f in s["per_frame"])'
grep -q "EAO" "$work/stdout" || fail "benchmark does not print EAO: $(cat "$work/stdout")"

if [ "$failures" -eq 0 ]; then echo "eval scores boxes: all checks passed"; else echo "eval scores boxes: $failures failed"; exit 1; fi
