#!/usr/bin/env bash
# A full disk: the error names the file that could not be written and the system's reason, and
# the partial dataset is left for --resume, which the error says, and that it holds the space.
# Needs a private mount namespace (unshare) for a small tmpfs.
# Usage: test_full_disk.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"

if ! unshare -Urm true 2>/dev/null; then
  skip "no private mount namespace here (unshare -Urm); full disk not checked"
  finish "full disk"
fi
mkdir -p "$work/disk"
unshare -Urm sh -c 'mount -t tmpfs -o size=160k tmpfs "$1" && "$2" render "$3" --out "$1/out" --quiet; echo "rc=$?"; ls "$1"' \
  sh "$work/disk" "$bin" "$good" >"$work/stdout" 2>"$work/stderr"
grep -q "^rc=1$" "$work/stdout" || fail "a full disk gave $(grep rc= "$work/stdout"), expected exit 1"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "expected one line on stderr: $(cat "$work/stderr")"
grep -q "No space left on device" "$work/stderr" || fail "the system's reason is not given: $(cat "$work/stderr")"
grep -Eq "out\.partial/[^ ]+: " "$work/stderr" || fail "the file is not named: $(cat "$work/stderr")"
grep -q "^out.partial$" "$work/stdout" || fail "the partial dataset was not left: $(cat "$work/stdout")"
grep -q -- "--resume, or delete it to free its space" "$work/stderr" || fail "nothing says the partial dataset holds the space or that --resume continues: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "full disk: all checks passed"; else echo "full disk: $failures failed"; exit 1; fi
