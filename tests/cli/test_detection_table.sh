#!/usr/bin/env bash
# docs/detection.md's small results table is what scripts/detection_results.sh makes of the landed
# code: the script run again on the same few frames must print it line for line (so a change of
# the figures shows here, and the big tables are remade by the same script).
# Usage: test_detection_table.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
doc="$src/docs/detection.md"
# The marker before the table holds the command that made it.
command=$(grep -o '<!-- made by: scripts/detection_results.sh --frames [^>]*-->' "$doc" | head -1 |
  sed 's/<!-- made by: scripts\/detection_results.sh //; s/ -->$//')
[ -n "$command" ] || { fail "docs/detection.md has no small table made by scripts/detection_results.sh --frames"; exit 1; }
awk -v m="<!-- made by: scripts/detection_results.sh $command -->" '
  $0 == m { on = 1; next } on && /^<!-- end -->/ { exit } on { print }' "$doc" >"$work/committed.md"
# shellcheck disable=SC2086
LADARSIM_BIN="$bin" bash "$src/scripts/detection_results.sh" --root "$work" $command >"$work/made.md" ||
  fail "scripts/detection_results.sh $command failed"
diff "$work/committed.md" "$work/made.md" >"$work/diff" ||
  fail "docs/detection.md's table differs from scripts/detection_results.sh $command (rerun it and commit the table): $(cat "$work/diff")"
if [ "$failures" -eq 0 ]; then echo "detection table: all checks passed"; else echo "detection table: $failures failed"; exit 1; fi
