#!/usr/bin/env python3
# first40.py MODEL_TAG [SCENARIO_DIR]: of the default scenario's first 40 frames (the CLI test's run), in how many
# the track nearest the drone (eval's 2 m gate) is called drone; reads SCENARIO_DIR/det-MODEL_TAG.json from score.py.
import json, math, sys
m=sys.argv[1]; d=sys.argv[2] if len(sys.argv) > 2 else 'sc/default'
G=json.load(open(f'{d}/ground_truth.json'))['frames']; D={f['frame']:f['objects'] for f in json.load(open(f'{d}/det-{m}.json'))['tracks']}
calls=[]
for f in G[:40]:
    for o in f['objects']:
        if o['class']!='drone': continue
        near=[(math.dist(t['centre_m'],o['box_sensor']['centre_m']),t['class']) for t in D.get(f['index'],[]) if not t['predicted']]
        near=[n for n in near if n[0]<=2]
        if near: calls.append(min(near)[1])
print(f"  default first 40: drone {calls.count('drone')}/{len(calls)}, last {calls[-1]}")
