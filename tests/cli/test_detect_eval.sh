#!/usr/bin/env bash
# detect and eval through the command line: detections record the dataset they were computed on,
# and eval refuses another dataset's.
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"
"$bin" render "$good" --out "$work/a" --quiet >/dev/null || fail "small scenario did not render"
"$bin" render "$good" --out "$work/b" --seed 8 --quiet >/dev/null || fail "small scenario did not render with seed 8"
"$bin" detect "$work/a" --lambda 180 >/dev/null 2>&1 || fail "detect failed"
"$bin" eval "$work/a" --detections "$work/a/detections-vrbnn.json" >/dev/null 2>&1 || fail "eval of its own dataset failed"
"$bin" eval "$work/b" --detections "$work/a/detections-vrbnn.json" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "eval with another dataset's detections exited $rc, expected 2"
grep -q "$work/a" "$work/stderr" && grep -q "not of $work/b" "$work/stderr" ||
  fail "the refusal does not name both datasets: $(cat "$work/stderr")"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "the refusal is not one line: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "detect/eval: all checks passed"; else echo "detect/eval: $failures failed"; exit 1; fi
