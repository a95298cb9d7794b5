#!/usr/bin/env bash
# What goes wrong is said in the user's terms, in one line (issue #34): a misspelt key is named as
# the unknown key it is, with what it meant; eval with nothing to score says so, never "nan"; a
# garbage PCD is not quoted byte for byte; a file system's refusal names the path and the reason
# without the library's wording; a full --frames is refused before rendering; Ctrl-C is honoured
# within a second.
# Usage: test_messages_in_user_terms.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"
scenario() { sed "s#\.\./\.\./assets#$src/assets#" "$good"; }

# One line on stderr saying $3, exit $2.
expect_line() {
  local what=$1 want_rc=$2 word=$3 rc=$4
  [ "$rc" -eq "$want_rc" ] || fail "$what: exit $rc, expected $want_rc"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$what: expected one line on stderr, got: $(head -c 600 "$work/stderr")"
  grep -q -- "$word" "$work/stderr" || fail "$what: the message does not say '$word': $(head -c 600 "$work/stderr")"
}

# A misspelt required key (docs/scenario.md's own example).
scenario | sed 's/"speed_mps"/"sped_mps"/' >"$work/typo.json"
"$bin" render "$work/typo.json" --out "$work/t" --quiet >/dev/null 2>"$work/stderr"
expect_line "a misspelt required key" 2 'objects\[1\].trajectory.sped_mps: unknown key; did you mean "speed_mps"' $?

# eval with nothing to score: a scene without a drone.
scenario | sed 's/"cue_object": 2/"cue_object": 0/' | python3 -c '
import json, sys
s = json.load(sys.stdin)
s["objects"] = [o for o in s["objects"] if o["class"] != "drone"]
json.dump(s, sys.stdout)' >"$work/nodrone.json"
"$bin" render "$work/nodrone.json" --out "$work/nd" --frames 2 --quiet >/dev/null 2>&1 || fail "render without a drone failed"
"$bin" detect "$work/nd" >/dev/null 2>&1 || fail "detect without a drone failed"
"$bin" eval "$work/nd" --detections "$work/nd/detections-vrbnn.json" >"$work/stdout" 2>"$work/stderr"
expect_line "eval with no target" 2 "nothing to score" $?
grep -q "had no ground truth" "$work/stderr" && fail "eval says the dataset had no ground truth: it has"
# eval of a target never detected (the building, subtracted as background) among no drone, bird
# or aircraft: says so, never "nan".
"$bin" detect "$work/nd" --target 1 >/dev/null 2>&1 || fail "detect --target 1 failed"
"$bin" eval "$work/nd" --detections "$work/nd/detections-vrbnn.json" >"$work/stdout" 2>"$work/stderr" || fail "eval failed: $(cat "$work/stderr")"
grep -qi "nan" "$work/stdout" && fail "eval prints nan: $(cat "$work/stdout")"
grep -q "nothing to score" "$work/stdout" || fail "eval does not say there is nothing to score: $(cat "$work/stdout")"

# A garbage PCD: named, not quoted.
"$bin" render "$good" --out "$work/g" --frames 1 --quiet >/dev/null 2>&1 || fail "render failed"
head -c 3000 /dev/urandom >"$work/g/frames/000000.pcd"
"$bin" detect "$work/g" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] || fail "a garbage PCD: exit $rc, expected 2"
LC_ALL=C grep -q '[^[:print:][:space:]]' "$work/stderr" && fail "a garbage PCD's bytes are printed: $(head -c 300 "$work/stderr" | od -c | head -3)"
grep -q "000000.pcd" "$work/stderr" || fail "a garbage PCD is not named: $(head -c 300 "$work/stderr")"

# A file system's refusal: the path and the reason, not "filesystem error: cannot create directories".
# On a read-only tmpfs (a private mount namespace), since root writes through chmod.
if unshare -Urm true 2>/dev/null; then
  mkdir -p "$work/ro"
  unshare -Urm sh -c 'mount -t tmpfs -o ro tmpfs "$1" && exec "$2" render "$3" --out "$1/ds" --quiet' \
    sh "$work/ro" "$bin" "$good" >/dev/null 2>"$work/stderr"
  expect_line "--out on a read-only file system" 1 "$work/ro/ds.partial: Read-only file system" $?
  grep -q "filesystem error" "$work/stderr" && fail "the library's wording: $(cat "$work/stderr")"
else
  skip "no private mount namespace here (unshare -Urm); the read-only file system case not checked"
fi

# --frames beyond the scenario file's cap, or beyond what the disk holds: refused at once.
"$bin" render "$good" --out "$work/huge" --frames 2147483647 --quiet >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -ne 0 ] && grep -q "from 1 to 10000000" "$work/stderr" || fail "--frames 2147483647: exit $rc, $(cat "$work/stderr")"
if unshare -Urm true 2>/dev/null; then
  mkdir -p "$work/disk"
  unshare -Urm sh -c 'mount -t tmpfs -o size=1m,nr_inodes=1000 tmpfs "$1" && exec "$2" render "$3" --out "$1/out" --frames 10000000 --quiet' \
    sh "$work/disk" "$bin" "$good" >/dev/null 2>"$work/stderr"
  expect_line "--frames beyond the disk" 2 "too many for the disk" $?
else
  skip "no private mount namespace here (unshare -Urm); --frames beyond the disk not checked"
fi

# Ctrl-C early in a render of millions of frames (on a tmpfs with room for them): honoured within
# a second, memory bounded.
if unshare -Urm true 2>/dev/null; then
  scenario >"$work/many.json"
  mkdir -p "$work/big"
  unshare -Urm sh -c 'mount -t tmpfs -o size=100t,nr_inodes=50m tmpfs "$1" && exec "$2" render "$3" --out "$1/out" --frames 9000000 --threads 1 --quiet' \
    sh "$work/big" "$bin" "$work/many.json" >/dev/null 2>"$work/stderr" &
  pid=$!
  sleep 3
  rss=$(awk '/VmHWM/ {print $2}' "/proc/$pid/status" 2>/dev/null)
  start=$(date +%s%N)
  kill -INT "$pid" 2>/dev/null
  while kill -0 "$pid" 2>/dev/null && [ $(( ($(date +%s%N) - start) / 1000000 )) -lt 10000 ]; do sleep 0.02; done
  waited=$(( ($(date +%s%N) - start) / 1000000 ))
  kill -0 "$pid" 2>/dev/null && { kill -KILL "$pid"; fail "Ctrl-C not honoured within 10 s"; }
  wait "$pid"
  rc=$?
  [ "$waited" -le 1500 ] || fail "Ctrl-C took $waited ms"
  [ "$rc" -eq 130 ] || fail "Ctrl-C gave exit $rc, expected 130: $(cat "$work/stderr")"
  grep -q "resume" "$work/stderr" || fail "Ctrl-C did not say how to continue: $(cat "$work/stderr")"
  [ "${rss:-0}" -lt 1000000 ] || fail "a render of 9000000 frames took $rss kB in its first seconds"
else
  skip "no private mount namespace here (unshare -Urm); Ctrl-C during a render of millions of frames not checked"
fi

finish messages
