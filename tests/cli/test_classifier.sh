#!/usr/bin/env bash
# train-classifier on a rendered campaign, detect --classifier, and eval's classification block:
# the command line end to end (how well it classifies is measured on the bundled datasets, not here).
source "$(dirname "$0")/harness.sh"
"$bin" campaign "$src/tests/cli/campaign_classes.json" --out "$work/c" --quiet >/dev/null 2>&1 || fail "the campaign did not render"
"$bin" train-classifier "$work/c" --out "$work/model.json" >"$work/stdout" 2>&1 || fail "train-classifier failed: $(cat "$work/stdout")"
grep -q "trained on [0-9]* rows from 4 sequences" "$work/stdout" || fail "train-classifier did not say what it trained on: $(cat "$work/stdout")"
grep -q "features by share of the gain: [a-z_0-9]* [01]\.[0-9]*" "$work/stdout" || fail "train-classifier did not say which features mattered: $(cat "$work/stdout")"
# Several campaigns are trained on together.
"$bin" train-classifier "$work/c" "$work/c" --out "$work/model2.json" >"$work/stdout2" 2>&1 || fail "train-classifier on two campaigns failed: $(cat "$work/stdout2")"
grep -q "trained on [0-9]* rows from 8 sequences" "$work/stdout2" || fail "train-classifier did not train on both campaigns: $(cat "$work/stdout2")"
# A missing campaign and a model file ladarsim did not write are refused in one line.
"$bin" train-classifier "$work/nowhere" --out "$work/m2.json" >/dev/null 2>"$work/stderr" && fail "train-classifier accepted a missing campaign"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "the refusal is not one line: $(cat "$work/stderr")"
echo '{}' >"$work/mine.json"
"$bin" train-classifier "$work/c" --out "$work/mine.json" >/dev/null 2>&1 && fail "train-classifier replaced a file it did not write"
test_dir=$(python3 -c 'import json,sys; c=json.load(open(sys.argv[1])); print([s["directory"] for s in c["sequences"] if s["split"]=="test"][0])' "$work/c/campaign.json")
"$bin" detect "$work/c/$test_dir" --classifier "$work/model.json" --out "$work/d.json" >/dev/null 2>&1 || fail "detect --classifier failed"
"$bin" eval "$work/c/$test_dir" --detections "$work/d.json" --json "$work/scores.json" >/dev/null 2>&1 || fail "eval failed"
python3 - "$work/d.json" "$work/scores.json" <<'PY' || fail "classes or classification missing: $(head -c 600 "$work/scores.json")"
import json, sys
d = json.load(open(sys.argv[1]))
objects = [o for f in d["tracks"] for o in f["objects"]]
assert objects and all(o["class"] in ("drone", "bird", "plane", "clutter") and 0 < o["class_confidence"] <= 1 or
                       o["class"] is None and o["class_confidence"] is None for o in objects)
# A track has no class (null) until it has shown a few frames with a cluster, the same few for every
# track, and never again after it has one.
young = {}
for o in objects:
    h = young.setdefault(o["track"], {"seen": 0, "classed": False, "seen_before_class": None})
    if o["class"] is None:
        assert not h["classed"], f"track {o['track']} lost its class"
    elif not h["classed"]:
        h["classed"], h["seen_before_class"] = True, h["seen"]
    h["seen"] += not o["predicted"]
waits = {h["seen_before_class"] for h in young.values() if h["classed"]}
assert len(waits) == 1 and min(waits) >= 1, f"tracks waited {waits} frames with a cluster for a class"
assert all(h["seen"] <= min(waits) for h in young.values() if not h["classed"])
c = json.load(open(sys.argv[2]))["classification"]
classes = ("drone", "bird", "plane", "clutter")
unclassified = sum(1 for h in young.values() if not h["classed"])
assert sum(c["unclassified"].values()) == unclassified
assert sum(c["confusion"][t][p] for t in classes for p in classes) + unclassified == c["tracks"] > unclassified
for k in classes:
    pc = c["per_class"][k]
    assert pc["tracks"] == sum(c["confusion"][k].values())  # the classified tracks; c["unclassified"][k] more
    assert pc["recall"] is None or 0 <= pc["recall"] <= 1
    assert pc["precision"] is None or 0 <= pc["precision"] <= 1
assert c["frames_to_settle"]["mean"] >= 1
PY
# Without --classifier detect classifies with the bundled model; `--classifier none` does not.
"$bin" detect "$work/c/$test_dir" --out "$work/bundled.json" >/dev/null 2>&1 || fail "detect with the bundled classifier failed"
"$bin" detect "$work/c/$test_dir" --classifier none --out "$work/none.json" >/dev/null 2>&1 || fail "detect --classifier none failed"
python3 - "$work/bundled.json" "$work/none.json" <<'PY' || fail "the bundled classifier's classes are missing, or --classifier none wrote classes"
import json, sys
bundled = [o for f in json.load(open(sys.argv[1]))["tracks"] for o in f["objects"]]
none = [o for f in json.load(open(sys.argv[2]))["tracks"] for o in f["objects"]]
assert bundled and all("class" in o and "class_confidence" in o for o in bundled)
assert none and not any("class" in o for o in none)
PY
finish "classifier"
