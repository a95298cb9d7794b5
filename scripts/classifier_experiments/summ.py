#!/usr/bin/env python3
# summ.py < score.py's lines: one line per dataset, drone precision / recall at the tracks' last frames, bird
# tracks called drone, frames the drone is called drone (of those followed), tracks too short for a class, and eval's confusion.
import json,sys
for l in sys.stdin:
    r=json.loads(l); c=r.get('confusion',{}); p,rc=r.get('drone_p_r',(None,None))
    bd=c.get('bird',{}).get('drone',0); nb=sum(c.get('bird',{}).values())
    fr=r['frames'].get('drone',{}); fd=fr.get('drone',0); ft=sum(v for k,v in fr.items() if k!='none')
    f=lambda x: '-' if x is None else f"{x:.2f}"
    print(f"  {r['dataset']:16s} P/R {f(p)}/{f(rc)} birds>drone {bd}/{nb} droneframes {fd}/{ft} unclassified {json.dumps(r.get('unclassified', {}))} conf {json.dumps(c)}")
