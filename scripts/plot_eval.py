#!/usr/bin/python3
"""Draws `ladarsim eval --json` output: per-frame L2 distance and IoU, like the paper's Fig. 12.

Usage: plot_eval.py EVAL.json OUT.png

Frames without a detection have no L2 (gaps); with none at all the L2 panel says so instead of
drawing an empty axis about 0. Scores of `ladarsim benchmark` also hold a supervised run: its
re-initialisations (IoU 1 by construction, the tracker placed on the ground truth) are marked as
vertical lines, not drawn as IoU, so that they do not squash the real curve: the IoU axis is
scaled to the IoUs measured. `eval`'s scores have no supervised run, and the plot draws none.
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def draw(e):
    per_frame = e["per_frame"]
    frames = [f["frame"] for f in per_frame]
    fig, (l2, iou) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    l2_values = [f["l2_m"] if f["l2_m"] is not None else float("nan") for f in per_frame]
    # Never "nan" in the title: a target detected in no frame has no mean L2, and says so.
    mean_l2 = f"mean L2 {e['mean_l2_m']:.3f} m" if e["mean_l2_m"] is not None else "no mean L2 (never detected)"
    supervised_run = "eao" in e
    title = f"{e.get('method', '')}: {mean_l2}, mean IoU {e['mean_iou']:.3f}"
    if supervised_run:
        title += f", EAO {e['eao']:.3f}, {e['failures']} failures"
    l2.set_title(title)
    l2.set_ylabel("L2 distance (m)")
    l2.grid(alpha=0.3)
    measured = [v for v in l2_values if not math.isnan(v)]
    if measured:
        l2.plot(frames, l2_values, "b.-")
        l2.set_ylim(0, max(measured) * 1.1 + 1e-3)
    else:
        l2.set_ylim(0, 1)
        l2.text(0.5, 0.5, "no detections: no L2 distance in any frame", transform=l2.transAxes,
                ha="center", va="center", fontsize=11, color="grey")
    ious = [f["iou"] for f in per_frame]
    supervised = [float("nan") if f.get("initialised") else f["supervised_iou"] for f in per_frame] if supervised_run else []
    iou.plot(frames, ious, "g.-", label="IoU")
    if supervised_run:
        iou.plot(frames, supervised, "r:", label="IoU, supervised (VOT resets)")
    resets = [f["frame"] for f in per_frame if f.get("initialised")]
    for k, frame in enumerate(resets):
        iou.axvline(frame, color="red", alpha=0.25, linewidth=1, label="supervised re-initialisation" if k == 0 else None)
    top = max([v for v in ious + supervised if not math.isnan(v)] + [0.0])
    iou.set_ylim(0, min(1.05, max(0.05, top * 1.15)))
    iou.set_ylabel("IoU")
    iou.set_xlabel("frame")
    iou.grid(alpha=0.3)
    iou.legend(fontsize=8)
    fig.tight_layout()
    return fig


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    fig = draw(json.load(open(sys.argv[1])))
    tmp = sys.argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=100)
    os.replace(tmp, sys.argv[2])


if __name__ == "__main__":
    main()
