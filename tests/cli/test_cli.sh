#!/usr/bin/env bash
# End-to-end checks of the ladarsim command line: bad input is one clear line, a non-zero exit,
# and nothing written; a good scenario writes a complete dataset.
# Usage: test_cli.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

# Each bad scenario: expected exit 2, one line on stderr naming the file and the field.
expect_error() {
  local scenario=$1 field=$2
  local out="$work/out-$(basename "$scenario" .json)"
  "$bin" render "$scenario" --out "$out" --quiet >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  [ "$rc" -eq 2 ] || fail "$scenario: exit code $rc, expected 2"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$scenario: expected one line on stderr, got: $(cat "$work/stderr")"
  grep -q "$(basename "$scenario")" "$work/stderr" || fail "$scenario: message does not name the file: $(cat "$work/stderr")"
  grep -qF "$field" "$work/stderr" || fail "$scenario: message does not name '$field': $(cat "$work/stderr")"
  [ ! -e "$out" ] || fail "$scenario: output directory was created"
}

expect_error "$src/tests/cli/bad/unknown_top_key.json" "framez"
expect_error "$src/tests/cli/bad/unknown_sensor_key.json" "sensor.scan.beams_azz"
expect_error "$src/tests/cli/bad/zero_beams.json" "sensor.scan.beams_az"
expect_error "$src/tests/cli/bad/wide_field.json" "sensor.scan.field_az_deg"
expect_error "$src/tests/cli/bad/missing_model.json" "objects[0].model"
expect_error "$src/tests/cli/bad/not_json.json" "not valid JSON"
expect_error "$work/does_not_exist.json" "cannot open"
expect_error "$src/tests/cli/bad/wrong_type.json" "render.frames"
expect_error "$src/tests/cli/bad/negative_range.json" "sensor.receiver.max_range_m"
expect_error "$src/tests/cli/bad/nan_position.json" "not valid JSON"
expect_error "$src/tests/cli/bad/duplicate_id.json" "objects[1].id"
expect_error "$src/tests/cli/bad/missing_background.json" "background.file"
expect_error "$src/tests/cli/bad/corrupt_map.json" "background.file: $src/tests/cli/bad/corrupt_map.pcd"
expect_error "$src/tests/cli/bad/truncated_model.json" "objects[0].model: $src/tests/cli/bad/truncated.glb"
expect_error "$src/tests/cli/bad/extends_missing.json" "extends: no such file"
expect_error "$src/tests/cli/bad/extends_bad_removal.json" "objects[0].remove"

# A good run: every file present, no temporaries left, frames identical with 1 and 2 threads, and
# with 12 (three frames rendered at once, whatever the machine's cores).
good="$src/tests/cli/small.json"
"$bin" render "$good" --out "$work/t1" --threads 1 --quiet >/dev/null || fail "small scenario did not render"
"$bin" render "$good" --out "$work/t2" --threads 2 --quiet >/dev/null || fail "small scenario did not render with 2 threads"
"$bin" render "$good" --out "$work/t12" --threads 12 --quiet >/dev/null || fail "small scenario did not render with 12 threads"
for f in manifest.json ground_truth.json frames/000000.pcd frames/000000.exr frames/000002.pcd frames/000002.exr; do
  [ -s "$work/t1/$f" ] || fail "missing $f"
done
[ -z "$(find "$work/t1" -name '*.tmp')" ] || fail "temporary files left behind"
for f in "$work"/t1/frames/*; do
  cmp -s "$f" "$work/t2/frames/$(basename "$f")" || fail "$(basename "$f") differs between 1 and 2 threads"
  cmp -s "$f" "$work/t12/frames/$(basename "$f")" || fail "$(basename "$f") differs between 1 and 12 threads (frames at once)"
done
cmp -s "$work/t1/ground_truth.json" "$work/t12/ground_truth.json" || fail "ground truth differs between 1 and 12 threads"

# A frame that fails among frames rendered at once (12 threads: frames 3 to 5 together) fails the
# run naming it, publishes nothing, and the frames kept resume to the dataset of a plain run.
"$bin" render "$good" --out "$work/f1" --frames 7 --threads 1 --quiet >/dev/null || fail "7-frame render failed"
"$bin" render "$good" --out "$work/f12" --frames 7 --threads 12 --quiet --fail-at-frame 4 >/dev/null 2>"$work/stderr"
[ $? -ne 0 ] || fail "a frame failing among frames at once did not fail the run"
grep -q "frame 4: failure injected" "$work/stderr" || fail "the failure does not name frame 4: $(cat "$work/stderr")"
[ ! -e "$work/f12" ] || fail "a failed run published a dataset"
[ -s "$work/f12.partial/frames/000003.pcd" ] || fail "the frame finished before the failed one in its batch was not kept"
"$bin" render "$good" --out "$work/f12" --frames 7 --threads 12 --quiet --resume >/dev/null || fail "resume after a failure failed"
for f in "$work"/f1/frames/* "$work/f1/ground_truth.json" "$work/f1/background.pcd"; do
  cmp -s "$f" "$work/f12/${f#"$work/f1/"}" || fail "$(basename "$f") differs after resuming frames at once"
done
cmp -s "$work/t1/ground_truth.json" "$work/t2/ground_truth.json" || fail "ground truth differs between 1 and 2 threads"
cmp -s "$work/t1/background.pcd" "$work/t2/background.pcd" || fail "initial map differs between 1 and 2 threads (surveyed while the frames render)"

# Rendering again into a dataset replaces it whole: no stale frames from the longer run survive.
"$bin" render "$good" --out "$work/t1" --frames 1 --quiet >/dev/null || fail "re-render into an existing dataset failed"
[ "$(ls "$work/t1/frames" | wc -l)" -eq 2 ] || fail "stale frames left after re-rendering: $(ls "$work/t1/frames")"
[ ! -e "$work/t1.partial" ] && [ ! -e "$work/t1.old" ] || fail "staging directories left behind"

# A directory that is not a dataset is never replaced.
mkdir -p "$work/precious" && echo keep >"$work/precious/notes.txt"
"$bin" render "$good" --out "$work/precious" --quiet >/dev/null 2>"$work/stderr"
[ $? -eq 2 ] || fail "rendering into a non-dataset directory did not exit 2"
grep -q "refusing to replace" "$work/stderr" || fail "no clear message for a non-dataset directory: $(cat "$work/stderr")"
[ "$(cat "$work/precious/notes.txt")" = keep ] || fail "a non-dataset directory was touched"

# Ctrl-C stops after the current frame, keeps the finished ones, and --resume gives the same data
# as an uninterrupted run.
"$bin" render "$good" --out "$work/whole" --frames 120 --threads 2 --quiet >/dev/null || fail "uninterrupted run failed"
"$bin" render "$good" --out "$work/cut" --frames 120 --threads 2 --quiet >/dev/null 2>"$work/stderr" &
pid=$!
sleep 0.3
kill -INT "$pid" 2>/dev/null
wait "$pid"
rc=$?
if [ -d "$work/cut.partial" ]; then
  [ "$rc" -eq 130 ] || fail "interrupted render exited $rc, expected 130"
  grep -q "resume" "$work/stderr" || fail "no hint to resume: $(cat "$work/stderr")"
  [ ! -e "$work/cut" ] || fail "an interrupted run published a dataset"
  [ -z "$(find "$work/cut.partial" -name '*.tmp')" ] || fail "an interrupted run left a temporary file"
fi
"$bin" render "$good" --out "$work/cut" --frames 120 --threads 1 --quiet --resume >/dev/null || fail "resume failed"
for f in "$work"/whole/frames/*; do
  cmp -s "$f" "$work/cut/frames/$(basename "$f")" || fail "$(basename "$f") differs after interrupt and resume"
done
cmp -s "$work/whole/ground_truth.json" "$work/cut/ground_truth.json" || fail "ground truth differs after interrupt and resume"
[ ! -e "$work/cut.partial" ] || fail "the staging directory survived a completed resume"

# table1: the JSON rows carry the fields the documentation promises.
"$bin" table1 --frames 1 --footprint-samples 4 --json "$work/table1.json" >/dev/null 2>&1 || fail "table1 failed"
for key in range_m paper_tp analytic_tp_0p5deg analytic_tp_0p65deg rendered_plate_mean rendered_plate_min \
           rendered_plate_max rendered_drone_mean; do
  [ "$(grep -o "\"$key\"" "$work/table1.json" | wc -l)" -eq 7 ] || fail "table1.json lacks $key in its 7 rows"
done

if [ "$failures" -eq 0 ]; then echo "cli: all checks passed"; else echo "cli: $failures failed"; exit 1; fi
