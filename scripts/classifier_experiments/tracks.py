#!/usr/bin/env python3
# tracks.py DIR MODEL_TAG: each track of DIR/det-MODEL_TAG.json that follows a target (2 m gate): its frames, the
# ground-truth ids it follows, its class at its last frame and where its class last changed.
import json, math, sys
d, tag = sys.argv[1], sys.argv[2]
D=json.load(open(f'{d}/det-{tag}.json')); G=json.load(open(f'{d}/ground_truth.json'))
gt={f['index']:f['objects'] for f in G['frames']}
tr={}
for f in D['tracks']:
    for t in f['objects']:
        if t.get('predicted'): continue
        best=None
        for o in gt.get(f['frame'],[]):
            dd=math.dist(t['centre_m'],o['box_sensor']['centre_m'])
            if dd<=2 and (best is None or dd<best[0]): best=(dd,o['id'])
        r=tr.setdefault(t['track'],{'first':f['frame'],'calls':[],'gt':{}})
        r['last']=f['frame']; r['calls'].append(t['class'])
        if best: r['gt'][best[1]]=r['gt'].get(best[1],0)+1
for k,r in tr.items():
    if not r['gt']: continue
    c=r['calls']
    print(k, r['first'], r['last'], r['gt'], 'last', c[-1], 'drone', c.count('drone'), 'bird', c.count('bird'), 'changes at', [i+r['first'] for i in range(1,len(c)) if c[i]!=c[i-1]][-6:])
