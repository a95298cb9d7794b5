#!/usr/bin/env bash
# Geometry that cannot be what the user meant is warned about once, before rendering: the sensor
# inside an object (whose walls then lie within the receiver's minimum range and return nothing,
# not returns at 1.65 mm, or farther, met in all six directions), a cue the gimbal cannot reach (parked at its 175 deg limit), a target
# beyond max_range_m. A sensible scenario gets no warning.
# Usage: test_geometry_warnings.sh LADARSIM_BINARY SOURCE_DIR
source "$(dirname "$0")/harness.sh"
models="$src/assets/models"

# scenario NAME SENSOR_POSITION DRONE_START: small.json's building and approaching drone.
scenario() {
  cat >"$work/$1.json" <<JSON
{
  "sensor": {"position_m": $2, "cue_object": 2},
  "render": {"frames": 4, "seed": 7, "footprint_samples": 9},
  "objects": [
    {"id": 1, "class": "building", "model": "$models/building.glb", "trajectory": {"type": "fixed", "position_m": [160, 0, 0]}},
    {"id": 2, "class": "drone", "model": "$models/quadcopter.glb",
     "trajectory": {"type": "approach", "start_m": $3, "towards_m": [0, 0, 4], "speed_mps": 15}}
  ]
}
JSON
}
# expect_warning NAME WORDS: exactly one warning line, containing WORDS, printed before the first frame.
expect_warning() {
  "$bin" render "$work/$1.json" --out "$work/out-$1" >"$work/stdout" 2>"$work/stderr" || fail "$1: render failed: $(cat "$work/stderr")"
  [ "$(grep -c "^warning" "$work/stderr")" -eq 1 ] || fail "$1: expected one warning: $(cat "$work/stderr")"
  grep "^warning" "$work/stderr" | grep -q "$2" || fail "$1: the warning does not say '$2': $(cat "$work/stderr")"
  [ "$(head -1 "$work/stderr" | cut -c1-7)" = warning ] || fail "$1: the warning came after rendering began: $(cat "$work/stderr")"
}

scenario sensible "[0, 0, 2]" "[120, 1, 4]"
"$bin" render "$work/sensible.json" --out "$work/out-sensible" >/dev/null 2>"$work/stderr" || fail "sensible: render failed"
grep -q "^warning" "$work/stderr" && fail "a sensible scenario is warned about: $(cat "$work/stderr")"

# The sensor inside the building, half a metre from its wall: warned, and no return from within the minimum range.
scenario inside "[169.5, 0, 7]" "[200, 1, 4]"
expect_warning inside "inside object 1 (building"
grep -q "minimum range" "$work/stderr" || fail "inside: the minimum range is not mentioned: $(cat "$work/stderr")"
python3 - "$work/out-inside/frames/000000.pcd" <<'PY' || fail "inside: returns closer than the minimum range"
import re, struct, sys
data = open(sys.argv[1], "rb").read()
head, _, body = data.partition(b"DATA binary\n")
h = dict(l.split(" ", 1) for l in head.decode().splitlines() if " " in l)
fields, sizes, types = h["FIELDS"].split(), list(map(int, h["SIZE"].split())), h["TYPE"].split()
n = int(h["POINTS"]); step = sum(sizes)
def column(name):
    k = fields.index(name); code = {("F", 4): "f", ("F", 8): "d", ("U", 1): "B", ("U", 2): "H", ("U", 4): "I"}[(types[k], sizes[k])]
    return [struct.unpack_from("<" + code, body, i * step + sum(sizes[:k]))[0] for i in range(n)]
# Surface returns (source 0); false alarms are noise drawn over the whole range gate.
close = [r for r, s in zip(column("range_m"), column("source")) if s == 0 and r < 5.0]
sys.exit(1 if close else 0)
PY

# Deep inside the building, its walls 6 to 10 m away: warned as well (before, only the gimbal
# was, and the inside walls' returns followed).
scenario deep "[160, 0, 7]" "[200, 1, 4]"
"$bin" render "$work/deep.json" --out "$work/out-deep" --frames 1 >/dev/null 2>"$work/stderr" || fail "deep: render failed: $(cat "$work/stderr")"
grep "^warning" "$work/stderr" | grep -q "inside object 1 (building" || fail "deep: the sensor inside the building is not warned about: $(cat "$work/stderr")"

# The cue behind the sensor: the gimbal's +-175 deg cannot reach 180 deg.
scenario behind "[0, 0, 2]" "[-120, 0, 4]"
expect_warning behind "175"
grep "^warning" "$work/stderr" | grep -q "cue" || fail "behind: the cue is not named: $(cat "$work/stderr")"

# The drone 5 km away, the paper LADAR's max_range_m 3000.
scenario far "[0, 0, 2]" "[5000, 1, 4]"
expect_warning far "max_range_m"
grep "^warning" "$work/stderr" | grep -q "object 2 (drone" || fail "far: the object is not named: $(cat "$work/stderr")"

if [ "$failures" -eq 0 ]; then echo "geometry warnings: all checks passed"; else echo "geometry warnings: $failures failed"; exit 1; fi
