#!/usr/bin/env bash
# EXR range images: each pixel is the beam's first return, with the strongest return's range and
# intensity as their own channels; an empty pixel's object id (4294967294) differs from a false
# alarm's (4294967295); the README gives each preset's image size. Read with an independent
# Python reader and checked against the frame's PCD.
# Usage: test_exr_range_images.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"

"$bin" render "$src/tests/cli/small.json" --out "$work/d" --frames 2 --quiet >/dev/null 2>&1 || fail "render failed"
PYTHONPATH="$src/tests/cli" python3 - "$work/d/frames/000001" <<'PY' || fail "the range image does not hold what it should"
import sys
from read_dataset import read_exr, read_pcd
w, h, ch, attrs = read_exr(sys.argv[1] + ".exr")
pcd = read_pcd(sys.argv[1] + ".pcd")
bad = []
for name in ("range_m", "intensity", "object_id", "strongest_range_m", "strongest_intensity"):
    if name not in ch: bad.append("no channel " + name)
if bad: print(bad); sys.exit(1)
beams = {}
for i in range(len(pcd["range_m"])):
    beams.setdefault((pcd["row"][i], pcd["column"][i]), []).append(
        (pcd["return_index"][i], pcd["range_m"][i], pcd["intensity"][i], pcd["object_id"][i]))
several = 0
for row in range(h):
    for col in range(w):
        rs = sorted(beams.get((row, col), []))
        oid, rng = ch["object_id"][row][col], ch["range_m"][row][col]
        if not rs:
            if oid != 4294967294 or rng != 0: bad.append(("empty pixel", row, col, oid, rng))
            continue
        first, strongest = rs[0], max(rs, key=lambda r: r[2])
        several += len(rs) > 1
        if abs(rng - first[1]) > 1e-3 or oid != first[3]: bad.append(("not the first return", row, col))
        if abs(ch["strongest_range_m"][row][col] - strongest[1]) > 1e-3 or abs(ch["strongest_intensity"][row][col] - strongest[2]) > 1e-3 * max(1, strongest[2]):
            bad.append(("not the strongest return", row, col))
if bad: print(bad[:5], len(bad)); sys.exit(1)
print("pixels with several returns:", several)
PY

# The documentation: first return, the strongest's channels, the image size per sensor.
grep -q "first return" "$src/README.md" || fail "README does not say each pixel is the first return"
grep -q "strongest_range_m" "$src/README.md" || fail "README does not name the strongest return's channels"
grep -q "4294967294" "$src/README.md" || fail "README does not give the empty pixel's object id"
grep -q "3600 x 16" "$src/README.md" || fail "README does not give the VLP-16's image size"
grep -q "frames/NNNNNN.exr\`: 150 x 20 range images" "$src/README.md" && fail "README still gives 150 x 20 as every image's size"

if [ "$failures" -eq 0 ]; then echo "exr range images: all checks passed"; else echo "exr range images: $failures failed"; exit 1; fi
