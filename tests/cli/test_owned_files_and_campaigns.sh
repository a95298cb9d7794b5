#!/usr/bin/env bash
# What ladarsim writes one file at a time into a directory of the user's (sensor from-ouster --out,
# eval --json) and a campaign's directory are listed in .ladarsim-owned as a dataset's entries are
# (issue #34): a second run replaces its own file without --force, yet a file of the user's is
# still refused; such a directory does not become one a render may write a dataset into; a
# campaign lists its entries, a campaign begun before the list is taken up, and a directory holding
# a spec.json of the user's is refused whatever it holds.
# Usage: test_owned_files_and_campaigns.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"
tiny="$src/tests/cli/campaign_tiny.json"
sums() { (cd "$1" && find . -type f ! -name .ladarsim-owned -print0 | sort -z | xargs -0 md5sum); }

# eval --json twice into a directory of the user's: the second replaces what the first wrote.
"$bin" render "$good" --out "$work/d" --frames 2 --quiet >/dev/null 2>&1 || fail "render failed"
"$bin" detect "$work/d" >/dev/null 2>&1 || fail "detect failed"
mkdir -p "$work/mine"
echo "my notes" >"$work/mine/notes.txt"
for run in first second; do
  "$bin" eval "$work/d" --detections "$work/d/detections-vrbnn.json" --json "$work/mine/scores.json" >/dev/null 2>"$work/stderr" ||
    fail "eval --json, $run run: $(cat "$work/stderr")"
done
grep -qx "scores.json" "$work/mine/.ladarsim-owned" 2>/dev/null || fail "eval --json did not list scores.json as ladarsim's"

# sensor from-ouster likewise; a file of the user's is still refused.
if [ -d "$shared_data/ouster" ]; then
  meta="$shared_data/ouster/OS-1-32-G_v2.1.1_1024x10.json"
  for run in first second; do
    "$bin" sensor from-ouster "$meta" --out "$work/mine/os1.json" >/dev/null 2>"$work/stderr" ||
      fail "from-ouster, $run run: $(cat "$work/stderr")"
  done
  grep -qx "os1.json" "$work/mine/.ladarsim-owned" 2>/dev/null || fail "from-ouster did not list os1.json as ladarsim's"
  echo '{"my": "sensor"}' >"$work/mine/unit.json"
  "$bin" sensor from-ouster "$meta" --out "$work/mine/unit.json" >/dev/null 2>"$work/stderr"
  [ $? -eq 2 ] && grep -q -- "--force" "$work/stderr" || fail "from-ouster over the user's unit.json: $(cat "$work/stderr")"
  grep -q '"my"' "$work/mine/unit.json" || fail "from-ouster replaced the user's unit.json"
else
  skip "$shared_data/ouster absent, from-ouster not checked"
fi

# The listed directory is still the user's: no dataset is rendered into it.
before=$(sums "$work/mine")
"$bin" render "$good" --out "$work/mine" --frames 1 --quiet >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] && [ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -q "holds no dataset" "$work/stderr" ||
  fail "a render into the user's directory holding loose ladarsim files: exit $rc, $(cat "$work/stderr")"
[ "$before" = "$(sums "$work/mine")" ] || fail "the user's directory was changed"

# A campaign lists what it writes, and a render into it is refused.
"$bin" campaign "$tiny" --out "$work/c" --quiet >/dev/null 2>"$work/stderr" || fail "campaign failed: $(cat "$work/stderr")"
for entry in spec.json sequences campaign.json card.md card-targets.png; do
  grep -qx "$entry" "$work/c/.ladarsim-owned" 2>/dev/null || fail "the campaign's $entry is not listed as ladarsim's"
done
"$bin" render "$good" --out "$work/c" --frames 1 --quiet >/dev/null 2>"$work/stderr"
[ $? -eq 2 ] && grep -q "holds no dataset" "$work/stderr" || fail "a render into a campaign: $(cat "$work/stderr")"
# A campaign begun before the list (its spec.json this run's record) is taken up, and listed.
rm -f "$work/c/.ladarsim-owned"
"$bin" campaign "$tiny" --out "$work/c" --quiet >/dev/null 2>"$work/stderr" || fail "a campaign without its list was not taken up: $(cat "$work/stderr")"
grep -qx "spec.json" "$work/c/.ladarsim-owned" 2>/dev/null || fail "the campaign taken up was not listed"

# A directory holding a spec.json of the user's (not the campaign's record, not even JSON): refused
# in one line, untouched.
mkdir -p "$work/project"
echo "openapi: 3.0.0" >"$work/project/spec.json"
before=$(sums "$work/project")
"$bin" campaign "$tiny" --out "$work/project" --quiet >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] && [ "$(wc -l <"$work/stderr")" -eq 1 ] && grep -q "is neither empty nor a campaign" "$work/stderr" ||
  fail "a campaign into a directory with the user's spec.json: exit $rc, $(cat "$work/stderr")"
[ "$before" = "$(sums "$work/project")" ] && [ ! -e "$work/project/.ladarsim-owned" ] || fail "the user's directory was changed"

finish "owned files and campaigns"
