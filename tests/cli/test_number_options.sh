#!/usr/bin/env bash
# Whole-number options: a value outside the range, a word, a negative seed: one clear line naming
# the option, the value and the valid range; nothing is rendered or silently wrapped around.
# Usage: test_number_options.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"

# expect_bad ARGS... : non-zero exit, one line on stderr naming the option, the value and a range.
expect_bad() {
  local option=$1 value=$2 range=$3; shift 3
  "$bin" "$@" "$option" "$value" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  [ "$rc" -ne 0 ] || fail "$* $option $value: accepted"
  local msg; msg=$(grep -v "^Run with --help" "$work/stderr")
  [ "$(echo "$msg" | wc -l)" -eq 1 ] || fail "$option $value: expected one line: $(cat "$work/stderr")"
  echo "$msg" | grep -qF -- "$option" || fail "$option $value: the option is not named: $msg"
  echo "$msg" | grep -qF -- "'$value'" || fail "$option $value: the value is not quoted: $msg"
  echo "$msg" | grep -qF -- "$range" || fail "$option $value: the range '$range' is not given: $msg"
  echo "$msg" | grep -q "[0-9]\{25,\}\|not in range" && fail "$option $value: unreadable message: $msg"
  [ ! -e "$work/out" ] || fail "$option $value: an output was written"
  rm -rf "$work/out"
}
expect_bad --frames 0 "from 1 to 10000000" render "$good" --out "$work/out"
expect_bad --frames abc "from 1 to 10000000" render "$good" --out "$work/out"
expect_bad --frames 2.5 "from 1 to 10000000" render "$good" --out "$work/out"
expect_bad --seed -1 "from 0 to 18446744073709551615" render "$good" --out "$work/out"
expect_bad --seed 18446744073709551616 "from 0 to 18446744073709551615" render "$good" --out "$work/out"
expect_bad --threads -2 "from 0 to" render "$good" --out "$work/out"
expect_bad --frames 0 "from 1 to" table1
expect_bad --threads -2 "from 0 to" table1
expect_bad --target -3 "from 1 to 4294967295" detect "$work"

# Good values still work, and the largest seed is the seed given.
"$bin" render "$good" --out "$work/ok" --frames 1 --seed 18446744073709551615 --quiet >/dev/null 2>"$work/stderr" \
  || fail "the largest seed was refused: $(cat "$work/stderr")"
grep -q '"seed": 18446744073709551615' "$work/ok/manifest.json" || fail "the seed in the manifest is not the one given"

if [ "$failures" -eq 0 ]; then echo "number options: all checks passed"; else echo "number options: $failures failed"; exit 1; fi
