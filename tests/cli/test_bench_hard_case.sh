#!/usr/bin/env bash
# `ladarsim bench --hard-case TEXT` runs only the hard cases whose name holds TEXT: a line per
# setting on stdout, the same figures in the JSON (the default setting marked), nothing else run;
# a text that names no case is an error naming the option.
# Usage: test_bench_hard_case.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
cd "$src"

"$bin" bench --quick --hard-case "horizontal, 200 m" --json "$work/bench.json" >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "bench --hard-case exited $rc: $(cat "$work/stderr")"
lines=$(grep -c "^straight edge, horizontal, 200 m, " "$work/stdout")
[ "$lines" -eq 3 ] || fail "expected a line for each of the 3 quick settings, got $lines: $(cat "$work/stdout")"
grep -q "adaptive 0.050: count .*, range error mean .* missing beams, .* rays/beam, .* beams/s" "$work/stdout" ||
  fail "the default setting's line does not give its errors and speed: $(cat "$work/stdout")"
/usr/bin/python3 - "$work/bench.json" <<'PY' || fail "the JSON does not hold the one case with its default setting marked"
import json, sys
b = json.load(open(sys.argv[1]))
assert set(b) == {"hard_cases", "quick"}, b.keys()
[case] = b["hard_cases"]
assert case["case"] == "straight edge, horizontal, 200 m", case["case"]
assert sum(1 for s in case["settings"] if s.get("default")) == 1
assert all(s["beams_per_s"] > 0 and s["rays_per_beam"] > 0 for s in case["settings"])
PY

"$bin" bench --quick --hard-case "no such case" >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -ne 0 ] || fail "an unknown hard case exited 0"
grep -q -- "--hard-case: no hard case's name contains 'no such case'" "$work/stderr" ||
  fail "the unknown hard case is not named: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "bench --hard-case: all checks passed"; else echo "bench --hard-case: $failures failed"; exit 1; fi
