#!/usr/bin/env bash
# Nothing of the user's is lost (issue #34): ladarsim replaces or deletes only what its
# .ladarsim-owned list says it wrote; a directory without that list is refused unless empty; user
# files named like ladarsim's survive a re-render (checksums) while ladarsim's own stale outputs
# go; a batch whose scenarios share a name, a sensor file already there, an import onto a rendered
# dataset, a second render into the same --out and a render over an interrupted one are refused
# in one line before anything is written.
# Usage: test_nothing_lost.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"
data="$shared_data"

sums() { (cd "$1" && find . -type f ! -name .ladarsim-owned -print0 | sort -z | xargs -0 md5sum); }
# Exit 2, one line on stderr saying $2, no frame rendered.
expect_refusal() {
  local what=$1 word=$2 rc=$3
  [ "$rc" -eq 2 ] || fail "$what: exit $rc, expected 2"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$what: expected one line on stderr, got: $(cat "$work/stderr")"
  grep -q -- "$word" "$work/stderr" || fail "$what: the message does not say '$word': $(cat "$work/stderr")"
}

# A project of the user's that merely holds a manifest.json: refused, untouched.
mkdir -p "$work/proj/src"
echo '{"name": "my web app"}' >"$work/proj/manifest.json"
echo '{"mine": true}' >"$work/proj/ground_truth.json"
echo 'console.log(1)' >"$work/proj/src/app.js"
before=$(sums "$work/proj")
"$bin" render "$good" --out "$work/proj" --frames 1 --quiet >/dev/null 2>"$work/stderr"
expect_refusal "a directory with someone else's manifest.json" "refusing to replace" $?
[ "$before" = "$(sums "$work/proj")" ] || fail "the user's project was changed"
[ ! -e "$work/proj.partial" ] || fail "the refused render staged a dataset"

# Re-rendering keeps the user's files named like ladarsim's and removes ladarsim's stale outputs.
"$bin" render "$good" --out "$work/d" --frames 2 --quiet >/dev/null 2>"$work/stderr" || fail "render failed: $(cat "$work/stderr")"
echo '{"boxes": "drawn by hand"}' >"$work/d/detections-handlabelled.json"
echo '{"my": "summary"}' >"$work/d/eval-summary.json"
"$bin" detect "$work/d" >/dev/null 2>&1 || fail "detect failed"
"$bin" eval "$work/d" --detections "$work/d/detections-vrbnn.json" --json "$work/d/eval-vrbnn.json" >/dev/null 2>&1 ||
  fail "eval failed"
[ -e "$work/d/detections-vrbnn.json" ] && [ -e "$work/d/eval-vrbnn.json" ] || fail "detect and eval wrote nothing"
# Detect and eval again replace their own outputs.
"$bin" detect "$work/d" >/dev/null 2>"$work/stderr" || fail "detect could not replace its own output: $(cat "$work/stderr")"
mine=$(md5sum "$work/d/detections-handlabelled.json" "$work/d/eval-summary.json")
"$bin" render "$good" --out "$work/d" --frames 1 --quiet >"$work/stdout" 2>"$work/stderr" || fail "re-render failed: $(cat "$work/stderr")"
[ "$mine" = "$(md5sum "$work/d/detections-handlabelled.json" "$work/d/eval-summary.json" 2>/dev/null)" ] ||
  fail "the user's detections-handlabelled.json or eval-summary.json was lost or changed in a re-render"
[ ! -e "$work/d/detections-vrbnn.json" ] && [ ! -e "$work/d/eval-vrbnn.json" ] ||
  fail "ladarsim's own stale detections or scores survived beside the new frames"
grep -q "detections-handlabelled.json" "$work/stdout" || fail "the summary does not name the kept files: $(cat "$work/stdout")"
# A file of the user's where detect would write: refused unless --force.
echo '{"mine": 1}' >"$work/d/detections-rbnn.json"
mine=$(md5sum <"$work/d/detections-rbnn.json")
"$bin" detect "$work/d" --method rbnn >/dev/null 2>"$work/stderr"
expect_refusal "detect over the user's file" "--force" $?
[ "$mine" = "$(md5sum <"$work/d/detections-rbnn.json")" ] || fail "detect replaced the user's detections-rbnn.json"
"$bin" detect "$work/d" --method rbnn --force >/dev/null 2>&1 || fail "detect --force failed"
# eval's outputs likewise, and a plot into a missing directory names the user's path.
echo '{"mine": 2}' >"$work/scores.json"
"$bin" eval "$work/d" --detections "$work/d/detections-rbnn.json" --json "$work/scores.json" >/dev/null 2>"$work/stderr"
expect_refusal "eval --json over the user's file" "scores.json" $?
grep -q mine "$work/scores.json" || fail "eval replaced the user's scores.json"
# benchmark writes its scores as eval does (report_scores): the same refusal, before the detector runs.
"$bin" benchmark "$work/d" --json "$work/scores.json" >/dev/null 2>"$work/stderr"
expect_refusal "benchmark --json over the user's file" "scores.json" $?
grep -q mine "$work/scores.json" || fail "benchmark replaced the user's scores.json"
"$bin" eval "$work/d" --detections "$work/d/detections-rbnn.json" --plot /nonexistent/e.png >/dev/null 2>"$work/stderr"
expect_refusal "eval --plot into a missing directory" "/nonexistent/e.png: --plot: its directory /nonexistent does not exist" $?

# A batch whose scenarios share a name: refused naming both, nothing rendered.
mkdir -p "$work/a" "$work/b"
sed "s#\.\./\.\./assets#$src/assets#" "$good" >"$work/a/x.json"
sed "s#\.\./\.\./assets#$src/assets#" "$good" >"$work/b/x.json"
"$bin" render "$work/a/x.json" "$work/b/x.json" --out "$work/batch" --frames 1 --quiet >/dev/null 2>"$work/stderr"
expect_refusal "two scenarios named x.json" "a/x.json" $?
grep -q "b/x.json" "$work/stderr" || fail "the clash does not name both files: $(cat "$work/stderr")"
[ ! -e "$work/batch" ] || fail "the refused batch rendered something"
"$bin" render "$work/a/x.json" "$work/a/x.json" --out "$work/batch" --frames 1 --quiet >/dev/null 2>"$work/stderr"
expect_refusal "one scenario twice" "x.json" $?

# A second render into the same --out while one is writing there: one line, the first unharmed.
mkdir -p "$work/busy.partial"
flock "$work/busy.partial" "$bin" render "$good" --out "$work/busy" --frames 1 --quiet >/dev/null 2>"$work/stderr"
expect_refusal "a render into a locked --out" "another ladarsim run is writing there" $?
rmdir "$work/busy.partial"
"$bin" render "$good" --out "$work/busy" --frames 40 --threads 1 --quiet >/dev/null 2>"$work/first" &
first=$!
for _ in $(seq 100); do [ -e "$work/busy.partial/run.json" ] && break; sleep 0.05; done
"$bin" render "$good" --out "$work/busy" --frames 1 --quiet >/dev/null 2>"$work/stderr"
rc=$?
if kill -0 "$first" 2>/dev/null; then expect_refusal "a second render while the first runs" "another ladarsim run" $rc; fi
wait "$first" || fail "the first render failed beside the second: $(cat "$work/first")"
[ "$(ls "$work/busy/frames" | grep -c '\.pcd$')" -eq 40 ] || fail "the first render's dataset is incomplete"

# An interrupted render is not silently replaced; --resume with nothing to resume says so.
"$bin" render "$good" --out "$work/cut" --frames 200 --threads 1 --quiet >/dev/null 2>&1 &
pid=$!
for _ in $(seq 100); do [ -e "$work/cut.partial/frames/000000.log.json" ] && break; sleep 0.05; done
kill -INT "$pid"
wait "$pid"
if [ -d "$work/cut.partial" ]; then
  before=$(sums "$work/cut.partial")
  "$bin" render "$good" --out "$work/cut" --frames 200 --quiet >/dev/null 2>"$work/stderr"
  expect_refusal "a render over an interrupted one without --resume" "--resume" $?
  [ "$before" = "$(sums "$work/cut.partial")" ] || fail "the interrupted run's frames were replaced"
fi
"$bin" render "$good" --out "$work/fresh" --frames 1 --resume --quiet >/dev/null 2>"$work/stderr" || fail "--resume of nothing failed"
grep -q "nothing to resume\|no interrupted render" "$work/stderr" || fail "--resume with nothing to resume said nothing: $(cat "$work/stderr")"

# sensor from-ouster never replaces an existing file without --force; a directory is one line.
if [ -d "$data/ouster" ]; then
  meta="$data/ouster/OS-1-32-G_v2.1.1_1024x10.json"
  echo '{"my": "sensor"}' >"$work/mine.json"
  "$bin" sensor from-ouster "$meta" --out "$work/mine.json" >/dev/null 2>"$work/stderr"
  expect_refusal "from-ouster over an existing file" "--force" $?
  grep -q '"my"' "$work/mine.json" || fail "from-ouster replaced the user's file"
  "$bin" sensor from-ouster "$meta" --out "$work/mine.json" --force >/dev/null 2>&1 || fail "from-ouster --force failed"
  "$bin" sensor from-ouster "$meta" --out "$work/a" >/dev/null 2>"$work/stderr"
  expect_refusal "from-ouster into a directory" "is a directory" $?
  grep -q "filesystem error" "$work/stderr" && fail "a raw filesystem error: $(cat "$work/stderr")"
else
  skip "$data/ouster absent, from-ouster not checked"
fi

# import-velodyne onto a rendered dataset: refused, the dataset intact.
if [ -f "$data/vlp16/velodyne_vlp16.pcap" ]; then
  before=$(sums "$work/d")
  "$bin" import-velodyne "$data/vlp16/velodyne_vlp16.pcap" --out "$work/d" >/dev/null 2>"$work/stderr"
  expect_refusal "an import onto a rendered dataset" "rendered dataset" $?
  [ "$before" = "$(sums "$work/d")" ] || fail "the import changed the rendered dataset"
else
  skip "$data/vlp16/velodyne_vlp16.pcap absent, import onto a rendered dataset not checked"
fi

finish "nothing lost"
