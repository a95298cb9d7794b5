#!/usr/bin/env bash
# detect with a target the ground truth does not have, eval with detections of another run: one
# line in the user's terms (the option, the ids there are, the frame counts), not "frames[0]: no
# box for the target".
# Usage: test_target_messages.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"

"$bin" render "$good" --out "$work/d" --frames 10 --quiet >/dev/null 2>&1 || fail "render failed"

"$bin" detect "$work/d" --target 99 >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "detect --target 99 exited $rc, expected 2"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "detect --target 99: expected one line: $(cat "$work/stderr")"
grep -q -- "--target" "$work/stderr" && grep -q "99" "$work/stderr" || fail "detect --target 99: the option and value are not named: $(cat "$work/stderr")"
grep -q "1 (building)" "$work/stderr" && grep -q "2 (drone)" "$work/stderr" || fail "detect --target 99: the objects there are not listed: $(cat "$work/stderr")"
grep -q "no box for the target" "$work/stderr" && fail "detect --target 99: the old message: $(cat "$work/stderr")"

# Detections of a 10-frame run scored against the dataset re-rendered with 3 frames, and the other
# way: another dataset's detections, refused naming both.
"$bin" detect "$work/d" --out "$work/det10.json" >/dev/null 2>&1 || fail "detect failed"
"$bin" render "$good" --out "$work/d" --frames 3 --quiet >/dev/null 2>&1 || fail "re-render failed"
"$bin" detect "$work/d" --out "$work/det3.json" >/dev/null 2>&1 || fail "detect failed"
"$bin" render "$good" --out "$work/e" --frames 10 --quiet >/dev/null 2>&1 || fail "render failed"
for pair in "d det10.json" "e det3.json"; do
  set -- $pair
  "$bin" eval "$work/$1" --detections "$work/$2" >"$work/stdout" 2>"$work/stderr"
  rc=$?
  [ "$rc" -eq 2 ] || fail "eval $1 $2 exited $rc, expected 2"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "eval $1 $2: expected one line: $(cat "$work/stderr")"
  grep -q "$2" "$work/stderr" && grep -q "not of $work/$1" "$work/stderr" \
    || fail "eval $1 $2: the two datasets are not named: $(cat "$work/stderr")"
  grep -q "no box for the target" "$work/stderr" && fail "eval $1 $2: the old message: $(cat "$work/stderr")"
done
"$bin" eval "$work/d" --detections "$work/det3.json" >/dev/null 2>"$work/stderr" || fail "eval of matching detections failed: $(cat "$work/stderr")"
# The same dataset with a frame gone since detect ran: the two frame counts, in one line.
rm "$work/d/frames/000002.pcd"
"$bin" eval "$work/d" --detections "$work/det3.json" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "eval with a frame gone exited $rc, expected 2"
grep -q "3 frames" "$work/stderr" && grep -q "2" "$work/stderr" && [ "$(wc -l <"$work/stderr")" -eq 1 ] \
  || fail "eval with a frame gone: the two frame counts are not given in one line: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "target messages: all checks passed"; else echo "target messages: $failures failed"; exit 1; fi
