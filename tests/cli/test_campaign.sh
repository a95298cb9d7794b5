#!/usr/bin/env bash
# `ladarsim campaign` end to end: the bundled spec twice gives identical sequences; shards into
# one directory give the unsharded campaign; an interrupted campaign resumes to the same result;
# splits cover every sequence; bad specs are refused naming the key.
# Usage: test_campaign.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
tiny="$src/tests/cli/campaign_tiny.json"

# Every file two campaign directories share, byte for byte, but the manifests (timings, paths)
# and spec.json (the path of the spec).
same_campaign() {
  local a=$1 b=$2 what=$3
  cmp -s "$a/campaign.json" "$b/campaign.json" || fail "$what: campaign.json differs"
  local files
  files=$(cd "$a" && find sequences -type f ! -name manifest.json | sort)
  [ "$files" = "$(cd "$b" && find sequences -type f ! -name manifest.json | sort)" ] || fail "$what: the files differ"
  [ -n "$files" ] || fail "$what: no files"
  for f in $files; do cmp -s "$a/$f" "$b/$f" || fail "$what: $f differs"; done
}

# The bundled spec, 6 sequences of 4 frames, twice.
for run in a b; do
  "$bin" campaign "$src/assets/campaigns/drones.json" --out "$work/$run" --sequences 6 --frames 4 --threads 2 \
    >"$work/$run.out" 2>"$work/$run.err" || fail "the bundled spec did not render: $(cat "$work/$run.err")"
done
same_campaign "$work/a" "$work/b" "the bundled spec rendered twice"
grep -q "^wrote .*campaign.json: 6 sequences of 4 frames" "$work/a.out" || fail "no summary: $(cat "$work/a.out")"
grep -q "^campaign: 6/6 sequences, sequence 000005 frame 4/4, .* frames/s, about .* s left" "$work/a.err" ||
  fail "no progress line: $(cat "$work/a.err")"
/usr/bin/python3 - "$work/a" <<'PY' || fail "the index does not match the directory"
import json, pathlib, sys
d = pathlib.Path(sys.argv[1]); index = json.load(open(d / "campaign.json"))
seqs = index["sequences"]
assert [s["id"] for s in seqs] == list(range(6)), [s["id"] for s in seqs]
# 0.7, 0.15, 0.15 of 6 by largest remainder: 4, 1, 1.
splits = [s["split"] for s in seqs]
assert sorted(splits) == ["test", "train", "train", "train", "train", "val"], splits
assert index["splits"] == {"train": 4, "val": 1, "test": 1}, index["splits"]
for s in seqs:
    seq = d / s["directory"]
    scenario = json.load(open(d / s["scenario"]))
    manifest = json.load(open(seq / "manifest.json"))
    assert manifest["scenario"] == scenario and manifest["render"]["seed"] == s["seed"], s["id"]
    assert len(list((seq / "frames").glob("*.pcd"))) == 4
    truth = json.load(open(seq / "ground_truth.json"))
    by_class = {}
    for f in truth["frames"]:
        for o in f["objects"]:
            by_class[o["class"]] = by_class.get(o["class"], 0) + o["returns"]
    for c, n in by_class.items():
        assert s["returns_by_class"].get(c, 0) == n, (s["id"], c, n, s["returns_by_class"])
    assert [o["id"] for o in s["sampled"]["objects"]] == [o["id"] for o in scenario.get("objects", [])]
PY

# The card: its plots drawn, its tables the index's.
for png in card-targets.png card-balance.png card-visibility.png; do
  grep -qF "]($png)" "$work/a/card.md" 2>/dev/null || fail "card.md does not show $png"
  [ "$(head -c 8 "$work/a/$png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$png is not a PNG"
done
grep -q "^| train | 4 | 16 |$" "$work/a/card.md" && grep -q "^| val | 1 | 4 |$" "$work/a/card.md" ||
  fail "card.md's splits are not the index's: $(grep -A5 '## Splits' "$work/a/card.md")"
grep -q "^wrote .*card.md" "$work/a.out" || fail "the summary does not name the card: $(cat "$work/a.out")"

# Shards 0/2 and 1/2 into one directory equal the unsharded run (4 sequences of 2 frames).
"$bin" campaign "$tiny" --out "$work/whole" --quiet >/dev/null 2>"$work/err" || fail "the tiny spec failed: $(cat "$work/err")"
! grep -q "resume" "$work/err" || fail "a fresh campaign warned about resuming: $(head -1 "$work/err")"
"$bin" campaign "$tiny" --out "$work/sharded" --shard 0/2 --quiet >"$work/out" 2>"$work/err" || fail "shard 0/2 failed: $(cat "$work/err")"
grep -q "^2 of the campaign's 4 sequences are finished" "$work/out" || fail "shard 0/2 does not say what is left: $(cat "$work/out")"
[ ! -e "$work/sharded/campaign.json" ] || fail "shard 0/2 wrote an index of a campaign half rendered"
[ -d "$work/sharded/sequences/000000" ] && [ -d "$work/sharded/sequences/000002" ] && [ ! -e "$work/sharded/sequences/000001" ] ||
  fail "shard 0/2 did not render sequences 0 and 2 alone: $(ls "$work/sharded/sequences")"
"$bin" campaign "$tiny" --out "$work/sharded" --shard 1/2 --quiet >"$work/out" 2>"$work/err" || fail "shard 1/2 failed: $(cat "$work/err")"
same_campaign "$work/whole" "$work/sharded" "shards 0/2 and 1/2"

# The shards of an array job, started together on a fresh directory: the same campaign.
"$bin" campaign "$tiny" --out "$work/together" --shard 0/2 --quiet >/dev/null 2>"$work/err0" &
first=$!
"$bin" campaign "$tiny" --out "$work/together" --shard 1/2 --quiet >/dev/null 2>"$work/err1" || fail "shard 1/2 started together failed: $(cat "$work/err1")"
wait "$first" || fail "shard 0/2 started together failed: $(cat "$work/err0")"
same_campaign "$work/whole" "$work/together" "shards started together"
[ -z "$(find "$work/together" -maxdepth 1 -name 'spec.json.*' -o -maxdepth 1 -name 'campaign.json.*')" ] || fail "temporaries left behind"

# Run again: nothing to render, the index unchanged.
cp "$work/whole/campaign.json" "$work/index-before"
"$bin" campaign "$tiny" --out "$work/whole" --quiet >"$work/out" 2>"$work/err" || fail "a finished campaign run again failed"
grep -q "^rendered 0 sequences .*; 4 of this share were already there" "$work/out" || fail "a rerun rendered again: $(cat "$work/out")"
cmp -s "$work/whole/campaign.json" "$work/index-before" || fail "a rerun changed campaign.json"

# Stopped in the middle of sequence 1 (after 3 frames), as Ctrl-C would: exit 130, sequence 0
# finished, sequence 1's first frame kept; the same command again finishes the same campaign.
"$bin" campaign "$tiny" --out "$work/resumed" --stop-after-frames 3 --quiet >/dev/null 2>"$work/err"
rc=$?
[ "$rc" -eq 130 ] || fail "a stopped campaign exits $rc, expected 130"
grep -q "run the same command again to continue" "$work/err" || fail "no word on resuming: $(cat "$work/err")"
[ -f "$work/resumed/sequences/000000/manifest.json" ] && [ -f "$work/resumed/sequences/000001.partial/frames/000000.pcd" ] &&
  [ ! -e "$work/resumed/sequences/000001.partial/frames/000001.pcd" ] && [ ! -e "$work/resumed/campaign.json" ] ||
  fail "the stopped campaign did not keep sequence 0 and sequence 1's first frame"
touch -d '2001-01-01' "$work/resumed/sequences/000001.partial/frames/000000.pcd"
"$bin" campaign "$tiny" --out "$work/resumed" --quiet >"$work/out" 2>"$work/err" || fail "the resumed campaign failed: $(cat "$work/err")"
grep -q "^rendered 3 sequences .*; 1 of this share were already there" "$work/out" || fail "resume did not keep sequence 0: $(cat "$work/out")"
[ "$(stat -c %Y "$work/resumed/sequences/000001/frames/000000.pcd")" = "$(date -d '2001-01-01' +%s)" ] ||
  fail "the resumed sequence rendered its finished frame again"
same_campaign "$work/whole" "$work/resumed" "a stopped campaign resumed"

# Killed outright (SIGKILL: no chance to finish a frame or tidy up) inside sequence 1, with 18 of
# its 20 frames to go: the same command finishes the campaign to the files of a run never killed.
"$bin" campaign "$tiny" --out "$work/whole20" --frames 20 --quiet >/dev/null 2>"$work/err" || fail "20 frames: $(cat "$work/err")"
"$bin" campaign "$tiny" --out "$work/killed" --frames 20 --threads 1 --quiet >/dev/null 2>&1 &
pid=$!
for _ in $(seq 3000); do [ -e "$work/killed/sequences/000001.partial/frames/000002.pcd" ] && break; sleep 0.01; done
kill -KILL "$pid"
wait "$pid" 2>/dev/null
[ -d "$work/killed/sequences/000001.partial" ] && [ ! -e "$work/killed/sequences/000001" ] ||
  fail "the kill did not land inside sequence 1: $(ls "$work/killed/sequences")"
"$bin" campaign "$tiny" --out "$work/killed" --frames 20 --quiet >/dev/null 2>"$work/err" || fail "the killed campaign did not resume: $(cat "$work/err")"
same_campaign "$work/whole20" "$work/killed" "a killed campaign resumed"

# export-kitti on a campaign: every sequence's frames numbered on in the index's order, each
# split's frame numbers in its ImageSets file, the splits disjoint and covering every frame; label
# boxes grown to hold the returns, or ground truth's with --exact-boxes, as for one dataset.
"$bin" export-kitti "$work/whole" --out "$work/kitti" >"$work/out" 2>"$work/err" || fail "export-kitti of a campaign failed: $(cat "$work/err")"
grep -q "^exported 8 frames" "$work/out" || fail "export-kitti did not export 8 frames: $(cat "$work/out")"
"$bin" export-kitti "$work/whole" --out "$work/kitti-exact" --exact-boxes >"$work/out" 2>"$work/err" ||
  fail "export-kitti --exact-boxes of a campaign failed: $(cat "$work/err")"
/usr/bin/python3 - "$work/whole" "$work/kitti" "$work/kitti-exact" <<'PY' || fail "the campaign's export does not match its index"
import json, pathlib, sys
campaign, kitti, exact = (pathlib.Path(a) for a in sys.argv[1:4])
for directory, boxes in ((kitti, "holding the returns"), (exact, "exact")):
    record = json.load(open(directory / "ladarsim_export.json"))
    assert record["label_boxes"] == boxes, (directory, record["label_boxes"])
    labels = 0
    for frame in record["frames"]:
        lines = (directory / "training" / "label_2" / f"{frame['kitti']}.txt").read_text().splitlines()
        assert len(lines) == len(frame["labels"]), (directory, frame)
        labels += len(lines)
        if boxes == "exact":
            assert lines == [label["exact_label"] for label in frame["labels"]], (frame, lines)
    assert labels > 0, f"{directory}: no labels to check"
index = json.load(open(campaign / "campaign.json"))
expected, number = {"train": [], "val": [], "test": []}, 0
for s in index["sequences"]:
    for _ in range(s["frames"]):
        expected[s["split"]].append(f"{number:06d}")
        number += 1
for split, numbers in expected.items():
    listed = (kitti / "ImageSets" / f"{split}.txt").read_text().split()
    assert listed == numbers, (split, listed, numbers)
assert sorted(p.stem for p in (kitti / "training" / "velodyne").glob("*.bin")) == [f"{k:06d}" for k in range(number)]
record = json.load(open(kitti / "ladarsim_export.json"))
assert [d["directory"] for d in record["datasets"]] == [s["directory"] for s in index["sequences"]]
assert [d["split"] for d in record["datasets"]] == [s["split"] for s in index["sequences"]]
PY

# Refusals: exit 2, one line on stderr naming the key.
expect_refusal() {
  local what=$1 word=$2 rc=$3
  [ "$rc" -eq 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(wc -l <"$work/err")" -eq 1 ] || fail "$what: expected one line on stderr, got: $(cat "$work/err")"
  grep -qF -- "$word" "$work/err" || fail "$what: the message does not say '$word': $(cat "$work/err")"
}
# A variant of the tiny spec, edited by a Python statement on `s`, beside it (its models resolve).
variant() {
  /usr/bin/python3 - "$tiny" "$src/tests/cli/campaign_variant.json" "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); exec(sys.argv[3]); json.dump(s, open(sys.argv[2], "w"))
PY
  "$bin" campaign "$src/tests/cli/campaign_variant.json" --out "$work/refused" --quiet >/dev/null 2>"$work/err"
}
variant 's["sequnces"] = 3'; expect_refusal "a misspelt key" "campaign_variant.json: sequnces: unknown key" $?
variant 's["objects"][0]["rnage_m"] = 3'; expect_refusal "a misspelt object key" "objects[0].rnage_m: unknown key" $?
variant 's["objects"][0]["range_m"] = {"uniform": [300, 100]}'; expect_refusal "lo above hi" "objects[0].range_m.uniform: lo 300 is above hi 100" $?
variant 's["objects"][0]["range_m"] = {"uniform": [-5, 100]}'; expect_refusal "a bound out of range" "objects[0].range_m.uniform[0]: -5 is not a number from 0" $?
variant 's["atmosphere"]["visibility_km"] = {"log_uniform": [0, 5]}'; expect_refusal "a log-uniform from 0" "atmosphere.visibility_km.log_uniform[0]" $?
variant 's["objects"][1]["count"] = {"uniform": [0, 2.5]}'; expect_refusal "a fractional count" "objects[1].count.uniform[1]: 2.5 is not a whole number" $?
variant 's["objects"][0]["trajectory"] = {"choice": []}'; expect_refusal "an empty choice" "objects[0].trajectory.choice: is empty" $?
variant 's["sensor"]["weights"] = [1]'; expect_refusal "weights of another length" "sensor.weights: has 1 weights for 2 choices" $?
variant 's["splits"]["test"] = 0.5'; expect_refusal "shares above 1" "splits: the shares of train, val and test sum to 1.25" $?
variant 's["objects"][0]["trajectory"] = "winding"'; expect_refusal "a trajectory lacking its keys" "objects[0].heading_deg: required: trajectory winding" $?
variant 's["objects"][2]["speed_mps"] = 3'; expect_refusal "a key no trajectory uses" "objects[2].speed_mps: no trajectory type this group draws (fixed) uses it" $?
variant 's["objects"][0]["trajectory"] = "orbit"'; expect_refusal "an unknown trajectory" "objects[0].trajectory: \"orbit\" is not one of" $?
variant 's["objects"][0]["model"] = "nowhere.glb"'; expect_refusal "a missing model" "objects[0].model: no such file" $?
variant 's["sensor"]["choice"][1]["scan"]["bogus"] = 1'; expect_refusal "a bad sensor entry" "sensor.choice[1].scan.bogus: unknown key" $?
variant 's["sensor"]["choice"][0]["position_m"] = [0, 0, 1]'; expect_refusal "a sensor position" "sensor.choice[0].position_m: set by the campaign" $?
variant 's["render"]["seed"] = 3'; expect_refusal "a render seed" "render.seed: set by the campaign" $?
rm -f "$src/tests/cli/campaign_variant.json"
[ ! -e "$work/refused" ] || fail "a refused spec left a directory"

"$bin" campaign "$tiny" --out "$work/whole" --seed 6 --quiet >/dev/null 2>"$work/err"
expect_refusal "another seed into a campaign" "holds a campaign of another spec, seed or size" $?
mkdir -p "$work/mine" && echo x >"$work/mine/thesis.tex"
"$bin" campaign "$tiny" --out "$work/mine" --quiet >/dev/null 2>"$work/err"
expect_refusal "a user's directory" "is neither empty nor a campaign" $?
[ "$(ls "$work/mine")" = thesis.tex ] || fail "the user's directory was touched"
"$bin" campaign "$tiny" --out "$work/x" --shard 2/2 >/dev/null 2>"$work/err" && fail "shard 2/2 was accepted"
grep -v "^Run with --help" "$work/err" | grep -q -- "--shard: '2/2' is not a shard I/N with 0 <= I < N" || fail "shard 2/2: $(cat "$work/err")"
[ ! -e "$work/x" ] || fail "a refused shard left a directory"

if [ "$failures" -eq 0 ]; then echo "campaign: all checks passed"; else echo "campaign: $failures failed"; exit 1; fi
