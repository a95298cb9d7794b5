#!/usr/bin/env python3
"""score.py MODEL DIR... : detect with MODEL, eval --json; print track confusion and, per frame,
the class given to the track nearest each drone (within 2 m or inside its box)."""
import json, subprocess, sys, os, math
B = os.environ.get("LADARSIM", os.path.join(os.path.dirname(__file__), "../../build/apps/ladarsim"))
model = sys.argv[1]
tag = os.path.basename(model).replace(".json", "")
for d in sys.argv[2:]:
    det = f"{d}/det-{tag}.json"
    sc = f"{d}/eval-{tag}.json"
    r = subprocess.run([B, "detect", d, "--classifier", model, "--out", det, "--force"], capture_output=True, text=True)
    if r.returncode:
        r = subprocess.run([B, "detect", d, "--classifier", model, "--out", det], capture_output=True, text=True)
        if r.returncode: print(d, "detect failed", r.stderr[-300:]); continue
    r = subprocess.run([B, "eval", d, "--detections", det, "--json", sc], capture_output=True, text=True)
    cls = json.load(open(sc)).get("classification") if os.path.exists(sc) else None
    D = json.load(open(det)); G = json.load(open(f"{d}/ground_truth.json"))
    tr = {t["frame"]: t["objects"] for t in D["tracks"]}
    frames = {"drone": {}, "bird": {}, "plane": {}}
    for i, f in enumerate(G["frames"]):
        objs = tr.get(f["index"], tr.get(i, []))
        for o in f["objects"]:
            c = o["class"]
            if c not in frames: continue
            bc = o["box_sensor"]["centre_m"]; bs = o["box_sensor"]["size_m"]
            best, call = 1e9, "none"
            for t in objs:
                if t.get("predicted"): continue
                off = [t["centre_m"][k] - bc[k] for k in range(3)]
                dd = math.sqrt(sum(x * x for x in off))
                inside = all(abs(off[k]) <= 0.5 * bs[k] for k in range(3))
                if (dd <= 2.0 or inside) and dd < best: best, call = dd, t.get("class", "?")
            frames[c][call] = frames[c].get(call, 0) + 1
    name = os.path.basename(d.rstrip("/"))
    out = {"dataset": name}
    if cls:
        conf = {k: {p: n for p, n in v.items() if n} for k, v in cls["confusion"].items() if any(v.values())}
        out["confusion"] = conf
        out["unclassified"] = {k: n for k, n in cls.get("unclassified", {}).items() if n}
        pc = cls["per_class"].get("drone", {})
        out["drone_p_r"] = (pc.get("precision"), pc.get("recall"))
    out["frames"] = {k: v for k, v in frames.items() if v}
    print(json.dumps(out))
