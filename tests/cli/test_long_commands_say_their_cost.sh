#!/usr/bin/env bash
# Commands that run for minutes say how long in their help (issue 34: `table1` ran 9 minutes with no
# duration given, `bench --quick` 3 where its help said about a minute), and table1 takes --threads
# like render, its output not depending on it.
# Usage: test_long_commands_say_their_cost.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

"$bin" table1 --help >"$work/help" 2>&1 || fail "table1 --help failed"
grep -Eq "about [0-9]+ min on 2 cores" "$work/help" || fail "table1 --help gives no duration: $(cat "$work/help")"
grep -q -- "--threads" "$work/help" || fail "table1 --help has no --threads"

"$bin" bench --help >"$work/help" 2>&1 || fail "bench --help failed"
grep -- "--quick" "$work/help" | grep -Eq "about [0-9]+ min on 2 cores" \
  || fail "bench --help gives --quick no duration on 2 cores: $(grep -- --quick "$work/help")"

for t in 1 2; do
  "$bin" table1 --frames 1 --footprint-samples 4 --threads $t >"$work/table$t.md" 2>"$work/stderr$t" \
    || fail "table1 --threads $t failed: $(cat "$work/stderr$t")"
done
cmp -s "$work/table1.md" "$work/table2.md" || fail "table1's output depends on --threads: $(diff "$work/table1.md" "$work/table2.md")"

finish "long commands say their cost"
