#!/usr/bin/env bash
# Documentation a new user reads against what the program does: the field limits of each scan
# pattern (the VLP-16 preset's field is 360 deg, beyond a galvo's 180), and the footprint
# sampling a render uses by default (adaptive, not 16 sub-rays).
# Usage: test_docs_match_code.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

# What the program says: the VLP-16 preset's azimuth field, the default footprint sampling.
"$bin" sensor show --preset velodyne_vlp16 >"$work/vlp.json" 2>&1 || fail "sensor show failed"
grep -q '"field_az_deg": 360' "$work/vlp.json" || fail "the VLP-16 preset's field is not 360 deg: $(grep field_az "$work/vlp.json")"
"$bin" render "$src/tests/cli/small.json" --out "$work/d" --frames 1 --quiet >/dev/null 2>&1 || fail "render failed"
python3 - "$src/tests/cli/small.json" "$work/nosamples.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); del s["render"]["footprint_samples"]
for o in s["objects"]: o["model"] = sys.argv[1].rsplit("/", 1)[0] + "/" + o["model"]
json.dump(s, open(sys.argv[2], "w"))
PY
"$bin" render "$work/nosamples.json" --out "$work/n" --frames 1 --quiet >/dev/null 2>&1 || fail "render without footprint_samples failed"
grep -q '"footprint_samples": 0' "$work/n/manifest.json" || fail "the default footprint sampling is not adaptive (0)"

# What the documentation says.
sensor_md="$src/docs/sensor.md" table1_md="$src/docs/table1.md"
grep "galvo_raster" "$sensor_md" | grep -q "(at most 180)" && fail "docs/sensor.md gives 180 deg as the field limit without saying it is a galvo's alone"
grep -q "360" <(grep "spinning_head" "$sensor_md") || fail "docs/sensor.md does not say a spinning head's field is 360 deg"
grep -q "16 sub-rays per beam (the renderer's default)" "$table1_md" && fail "docs/table1.md calls 16 sub-rays the default"
grep -qi "adaptive.*default\|default.*adaptive" "$table1_md" || fail "docs/table1.md does not say adaptive sampling is the default"

if [ "$failures" -eq 0 ]; then echo "docs match code: all checks passed"; else echo "docs match code: $failures failed"; exit 1; fi
