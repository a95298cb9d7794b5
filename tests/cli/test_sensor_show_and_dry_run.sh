#!/usr/bin/env bash
# `sensor show FILE` reads the user's own sensor file as a preset is shown; `render --dry-run`
# checks a scenario and --out and states the cost (frames, beams, time, disk) writing nothing;
# progress estimates the time left (test_progress_not_a_terminal.sh).
# Usage: test_sensor_show_and_dry_run.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
good="$src/tests/cli/small.json"

cp "$src/assets/sensors/velodyne_vlp16.json" "$work/my_unit.json"
"$bin" sensor show "$work/my_unit.json" >"$work/file.json" 2>"$work/stderr" || fail "sensor show FILE failed: $(cat "$work/stderr")"
"$bin" sensor show --preset velodyne_vlp16 >"$work/preset.json" || fail "sensor show --preset failed"
cmp -s "$work/file.json" "$work/preset.json" || fail "sensor show FILE differs from the preset it copies"
echo '{"name": "half"}' >"$work/half.json"
"$bin" sensor show "$work/half.json" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] && grep -q "half.json: scan" "$work/stderr" || fail "an incomplete sensor file: exit $rc, $(cat "$work/stderr")"

"$bin" render "$good" --out "$work/d" --frames 50 --dry-run >"$work/stdout" 2>"$work/stderr" || fail "--dry-run failed: $(cat "$work/stderr")"
grep -q "50 frames of [0-9]* beams" "$work/stdout" || fail "--dry-run does not state frames and beams: $(cat "$work/stdout")"
grep -Eq "about [0-9.]+ (ms|s|min|h) to render" "$work/stdout" || fail "--dry-run does not estimate the time: $(cat "$work/stdout")"
grep -Eq "[0-9]+ (kB|MB|GB) on disk" "$work/stdout" || fail "--dry-run does not estimate the disk: $(cat "$work/stdout")"
[ ! -e "$work/d" ] && [ ! -e "$work/d.partial" ] || fail "--dry-run wrote something"
# What a render would refuse, a dry run refuses.
mkdir -p "$work/mine" && echo x >"$work/mine/x.txt"
"$bin" render "$good" --out "$work/mine" --dry-run >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] && grep -q "refusing to replace" "$work/stderr" || fail "--dry-run into a directory of the user's: exit $rc, $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "sensor show and dry run: all checks passed"; else echo "sensor show and dry run: $failures failed"; exit 1; fi
