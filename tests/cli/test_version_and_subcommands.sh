#!/usr/bin/env bash
# `ladarsim --version` prints the version, after a subcommand too; an unknown or missing subcommand
# is named, with the valid ones listed.
# Usage: test_version_and_subcommands.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

version=$(sed -n 's/^project(ladarsim VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
"$bin" --version >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "--version exited $rc"
grep -qx "ladarsim $version" "$work/stdout" || fail "--version does not print 'ladarsim $version': $(cat "$work/stdout" "$work/stderr")"

"$bin" rendr >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "an unknown subcommand exited $rc, expected 2"
grep -q "unknown subcommand 'rendr'" "$work/stderr" || fail "the unknown subcommand is not named: $(cat "$work/stderr")"
for c in render sensor table1 detect eval import-velodyne import-ouster export-kitti export-las make-assets preview view bench; do
  grep -q "$c" "$work/stderr" || fail "the valid subcommand $c is not listed: $(cat "$work/stderr")"
done
grep -q "A subcommand is required" "$work/stderr" && fail "an unknown subcommand is reported as a missing one"

"$bin" >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "no subcommand exited $rc, expected 2"
grep -q "render" "$work/stderr" || fail "no subcommand: the valid ones are not listed: $(cat "$work/stderr")"

# After a subcommand too, whatever it requires.
for args in "render --version" "sensor --version" "detect --version" "eval x --version"; do
  "$bin" $args >"$work/stdout" 2>"$work/stderr"
  rc=$?
  [ "$rc" -eq 0 ] && grep -qx "ladarsim $version" "$work/stdout" || fail "'$args' exited $rc: $(cat "$work/stdout" "$work/stderr")"
done

# A known subcommand still parses as before; its help hides the options for testing and says
# what --threads 0 means.
"$bin" render --help >"$work/stdout" 2>&1 || fail "render --help failed"
grep -q -- "--fail-at-frame" "$work/stdout" && fail "render --help lists the testing option --fail-at-frame"
grep -A1 -- "--threads" "$work/stdout" | grep -q "0, the default: all cores" || fail "render --help does not say what --threads 0 means: $(grep -A1 -- --threads "$work/stdout")"

if [ "$failures" -eq 0 ]; then echo "version and subcommands: all checks passed"; else echo "version and subcommands: $failures failed"; exit 1; fi
