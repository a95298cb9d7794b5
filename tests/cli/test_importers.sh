#!/usr/bin/env bash
# Recorded captures through the command line: import-velodyne and import-ouster write datasets whose
# manifest names the sensor that recorded them (read back here with Python's json, not our reader),
# detect runs on them with that sensor's geometry, and a sensor file made by `sensor from-ouster`
# renders. Skipped without the shared data.
source "$(dirname "$0")/harness.sh"
if [ ! -d "$shared_data/ouster" ] || [ ! -d "$shared_data/vlp16" ]; then skip "shared data not present: $shared_data"; finish importers; fi

manifest_geometry() {  # DIR -> "name beams_az beams_el"
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["sensor"]; d=s["derived"]; print(s["name"], d["beams_az"], d["beams_el"])' "$1/manifest.json"
}

"$bin" import-velodyne "$shared_data/vlp16/velodyne_vlp16.pcap" --out "$work/vlp" >/dev/null || fail "import-velodyne failed"
[ "$(manifest_geometry "$work/vlp")" = "velodyne_vlp16 1800 16" ] || fail "VLP-16 manifest: $(manifest_geometry "$work/vlp")"
"$bin" detect "$work/vlp" >/dev/null 2>"$work/stderr" || fail "detect on the VLP-16 capture failed: $(cat "$work/stderr")"

for unit in "OS-1-32-G_v2.1.1_1024x10 ouster_os-1-32-g 1024 32" "OS-2-128-U1_v2.3.0_1024x10 ouster_os-2-128 1024 128"; do
  set -- $unit
  "$bin" import-ouster "$shared_data/ouster/$1.pcap" --metadata "$shared_data/ouster/$1.json" --out "$work/$2" >"$work/stdout" ||
    fail "import-ouster $1 failed"
  grep -q "decoded 1 frames" "$work/stdout" || fail "import-ouster $1: $(cat "$work/stdout")"
  [ "$(manifest_geometry "$work/$2")" = "$2 $3 $4" ] || fail "$1 manifest: $(manifest_geometry "$work/$2")"
  [ -s "$work/$2/frames/000000.pcd" ] || fail "$1: no frame written"
  "$bin" detect "$work/$2" >/dev/null 2>"$work/stderr" || fail "detect on $1 failed: $(cat "$work/stderr")"
  # The sensor file made from the metadata is the bundled preset of the same name.
  "$bin" sensor from-ouster "$shared_data/ouster/$1.json" --out "$work/$2.json" >/dev/null || fail "sensor from-ouster $1 failed"
  python3 -c 'import json,sys; a=json.load(open(sys.argv[1])); b=json.load(open(sys.argv[2])); sys.exit(a != b)' \
    "$work/$2.json" "$src/assets/sensors/$2.json" || fail "assets/sensors/$2.json is not what sensor from-ouster makes"
done

# A scenario names the sensor file; one frame renders with the unit's 1024 x 32 raster.
cat >"$work/os1_scene.json" <<JSON
{"sensor": {"file": "ouster_os-1-32-g.json", "position_m": [0, 0, 1]}, "render": {"frames": 1},
 "objects": [{"id": 1, "class": "building", "model": "$src/assets/models/building.glb",
              "trajectory": {"type": "fixed", "position_m": [20, 0, 0]}}]}
JSON
"$bin" render "$work/os1_scene.json" --out "$work/os1_render" --quiet >/dev/null || fail "rendering with an Ouster sensor file failed"
python3 -c 'import json,sys; m=json.load(open(sys.argv[1])); sys.exit(m["sensor"]["derived"]["beams_el"] != 32)' \
  "$work/os1_render/manifest.json" || fail "the rendered manifest does not hold the Ouster sensor"

finish importers
