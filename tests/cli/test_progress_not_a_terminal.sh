#!/usr/bin/env bash
# Progress on a stderr that is not a terminal (a CI log, tee): whole lines, now and then, never a
# carriage return, and the last line ended; the time left is estimated as it goes.
# Usage: test_progress_not_a_terminal.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

"$bin" render "$src/tests/cli/small.json" --out "$work/d" --frames 40 2>"$work/stderr" >/dev/null || fail "render failed"
grep -q $'\r' "$work/stderr" && fail "render: a carriage return on a non-terminal stderr: $(od -c "$work/stderr" | head -3)"
grep -qx "frame 40/40.*" "$work/stderr" || fail "render: no whole line for the last frame: $(cat "$work/stderr")"
[ "$(tail -c1 "$work/stderr" | od -An -c | tr -d ' ')" = '\n' ] || fail "render: the last line is not ended"
[ "$(wc -l <"$work/stderr")" -le 12 ] || fail "render: more than occasional lines: $(wc -l <"$work/stderr")"
grep -Eq "^frame [0-9]+/40, about [0-9]+ s left$" "$work/stderr" || fail "render: no estimate of the time left: $(cat "$work/stderr")"

# table1 counts the frames it renders (7 ranges x 4 settings x --frames), not ranges.
"$bin" table1 --frames 2 --footprint-samples 4 2>"$work/stderr" >/dev/null || fail "table1 failed"
grep -q $'\r' "$work/stderr" && fail "table1: a carriage return on a non-terminal stderr"
grep -qx "frames 56/56" "$work/stderr" || fail "table1: no whole line for the last frame: $(cat "$work/stderr")"
grep -Eq "^frames [0-9]+/56, about [0-9]+ s left$" "$work/stderr" || fail "table1: no estimate of the time left: $(cat "$work/stderr")"

# On a terminal the one updating line stays (script(1) gives the command a pseudo-terminal).
if command -v script >/dev/null; then
  script -qec "'$bin' render '$src/tests/cli/small.json' --out '$work/t' --frames 5 >/dev/null" "$work/typescript" >/dev/null 2>&1
  grep -q $'\r''frame 5/5' "$work/typescript" || fail "no updating line on a terminal: $(od -c "$work/typescript" | head -5)"
else
  skip "script(1) absent (bsdutils); the updating line on a terminal not checked"
fi

finish progress
