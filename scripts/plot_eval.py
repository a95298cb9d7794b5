#!/usr/bin/python3
"""Draws `ladarsim eval --json` output: per-frame L2 distance and IoU, like the paper's Fig. 12.

Usage: plot_eval.py EVAL.json OUT.png
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    e = json.load(open(sys.argv[1]))
    frames = [f["frame"] for f in e["per_frame"]]
    fig, (l2, iou) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    l2.plot(frames, [f["l2_m"] if f["l2_m"] is not None else float("nan") for f in e["per_frame"]], "b.-")
    l2.set_ylabel("L2 distance (m)")
    l2.set_title(f"{e.get('method', '')}: mean L2 {e['mean_l2_m'] or float('nan'):.3f} m, mean IoU {e['mean_iou']:.3f}, "
                 f"EAO {e['eao']:.3f}, {e['failures']} failures")
    l2.grid(alpha=0.3)
    iou.plot(frames, [f["iou"] for f in e["per_frame"]], "g.-", label="IoU")
    iou.plot(frames, [f["supervised_iou"] for f in e["per_frame"]], "r:", label="IoU, supervised (VOT resets)")
    iou.set_ylabel("IoU")
    iou.set_xlabel("frame")
    iou.set_ylim(-0.05, 1.05)
    iou.grid(alpha=0.3)
    iou.legend(fontsize=8)
    fig.tight_layout()
    tmp = sys.argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=100)
    os.replace(tmp, sys.argv[2])


if __name__ == "__main__":
    main()
