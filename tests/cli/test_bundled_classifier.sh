#!/usr/bin/env bash
# The bundled track classifier on the program's own demo: the default scenario's drone, 2 km out
# and closing at 30 m/s in 5 Hz frames, is called a drone (a model that had learnt the training
# scenes' ranges and speeds called it a plane).
source "$(dirname "$0")/harness.sh"
"$bin" render "$src/assets/scenarios/default.json" --frames 40 --out "$work/d" --quiet >/dev/null 2>&1 || fail "the default scenario did not render"
"$bin" detect "$work/d" --out "$work/det.json" >/dev/null 2>&1 || fail "detect with the bundled classifier failed"
python3 - "$work/d/ground_truth.json" "$work/det.json" <<'PY' || fail "the default scenario's drone is not called a drone"
import json, math, sys
truth = json.load(open(sys.argv[1]))["frames"]
tracks = {f["frame"]: f["objects"] for f in json.load(open(sys.argv[2]))["tracks"]}
calls = []
for f in truth:
    for o in f["objects"]:
        if o["class"] != "drone":
            continue
        centre = o["box_sensor"]["centre_m"]
        # The track following it: the nearest within eval's 2 m gate.
        near = [(math.dist(t["centre_m"], centre), t["class"]) for t in tracks.get(f["index"], []) if not t["predicted"]]
        near = [n for n in near if n[0] <= 2.0]
        if near:
            calls.append(min(near)[1])
# A track has no class (null) until it has shown a few frames with a cluster: those frames, at the
# start, are not counted against it.
young = 0
while young < len(calls) and calls[young] is None:
    young += 1
classed = calls[young:]
drone = classed.count("drone")
print(f"the drone is followed in {len(calls)} of {len(truth)} frames, the first {young} without a class, "
      f"and called a drone in {drone} ({', '.join(sorted(map(str, set(classed))))})")
assert len(calls) >= 0.9 * len(truth) and young < 0.5 * len(calls) and None not in classed
assert drone >= 0.9 * len(classed) and classed[-1] == "drone"
PY
finish "bundled classifier"
