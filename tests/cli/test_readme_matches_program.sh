#!/usr/bin/env bash
# What the README tells a new user against what the program does (issue #34): its `eval` line,
# run as written, writes the scores the viewer shows (eval-*.json beside the run: the line had no
# --json); its Table 1 means are docs/table1.json's, which `table1 --json` wrote (five differed in
# the last digit); a misspelt required key of the user's own sensor file is named with what it
# meant, as in a scenario.
# Usage: test_readme_matches_program.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
readme="$src/README.md"

"$bin" render "$src/tests/cli/small.json" --out "$work/d" --frames 3 --quiet >/dev/null 2>&1 || fail "render failed"
"$bin" detect "$work/d" >/dev/null 2>&1 || fail "detect failed"
line=$(grep -m1 "^ *build/apps/ladarsim eval DIR" "$readme" | sed 's/#.*//')
[ -n "$line" ] || fail "README has no 'ladarsim eval DIR' line"
# The README's words, with this build's program and the dataset above (no shell evaluation).
read -r -a words <<<"$line"
args=()
for w in "${words[@]:1}"; do args+=("${w//DIR/$work/d}"); done
"$bin" "${args[@]}" >/dev/null 2>"$work/stderr" || fail "the README's eval line failed: $(cat "$work/stderr")"
# The viewer (apps/viewer/viewer.js) shows the scores of the run's eval-*.json.
scores=$(cd "$work/d" && ls eval-*.json 2>/dev/null | head -1)
[ -n "$scores" ] || fail "the README's eval line writes no eval-*.json, so the viewer shows no scores: $line"
[ -z "$scores" ] || grep -q '"per_frame"' "$work/d/$scores" || fail "$scores holds no per-frame scores for the viewer"

# README's Table 1 against docs/table1.json, as the README rounds it.
python3 - "$readme" "$src/docs/table1.json" <<'PY' || fail "README's Table 1 is not docs/table1.json's"
import json, re, sys
readme, rows = open(sys.argv[1]).read(), json.load(open(sys.argv[2]))
for r in rows:
    want = (f"| {r['range_m']:.0f} | {r['paper_tp']} | {r['analytic_tp_0p5deg']:.0f} | {r['analytic_tp_0p65deg']:.0f} | "
            f"{r['rendered_plate_mean']:.1f} | {r['rendered_drone_mean']:.1f} |")
    if want not in readme:
        got = re.search(rf"^\| {r['range_m']:.0f} \|.*$", readme, re.M)
        sys.exit(f"README: {got.group(0) if got else 'no row'}; docs/table1.json: {want}")
PY

# A misspelt required key in the user's sensor file.
python3 - "$src/assets/sensors/velodyne_vlp16.json" "$work/unit.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["scan"]["chanels"] = s["scan"].pop("channels")
json.dump(s, open(sys.argv[2], "w"))
PY
"$bin" sensor show "$work/unit.json" >/dev/null 2>"$work/stderr"
rc=$?
[ "$rc" -eq 2 ] && grep -q 'unit.json: scan.chanels: unknown key; did you mean "channels"' "$work/stderr" ||
  fail "a misspelt required key in a sensor file: exit $rc, $(cat "$work/stderr")"

finish "README matches the program"
