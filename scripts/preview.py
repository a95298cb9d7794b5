#!/usr/bin/python3
"""Draws a rendered dataset's frames with their ground-truth boxes into DIR/preview.png.

Usage: preview.py DATASET_DIR [--frames N]   (or: ladarsim preview DATASET_DIR [--frames N])

Each row is one frame: left, the whole field in azimuth/elevation, points coloured by range on
one scale for the whole dataset (false alarms in grey, left out of the scale and of the axes),
each object's box and label in its class's colour; right, a close-up of the first drone's box
(cross-range metres about its centre) with the points that hit it. Reads only the files a user gets (binary PCD frames and ground_truth.json).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.colors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PCD_TYPES = {("F", 4): "<f4", ("F", 8): "<f8", ("U", 1): "u1", ("U", 2): "<u2", ("U", 4): "<u4",
             ("I", 1): "i1", ("I", 2): "<i2", ("I", 4): "<i4"}


def read_pcd(path):
    """A binary PCD file as a numpy structured array."""
    with open(path, "rb") as f:
        header = {}
        while True:
            line = f.readline().decode("ascii").strip()
            if not line or line.startswith("#"):
                continue
            key, _, value = line.partition(" ")
            header[key] = value.split()
            if key == "DATA":
                break
        if header["DATA"][0] != "binary":
            sys.exit(f"{path}: DATA {header['DATA'][0]} is not supported (binary only)")
        dtype = np.dtype([(name, PCD_TYPES[(t, int(s))])
                          for name, t, s in zip(header["FIELDS"], header["TYPE"], header["SIZE"])])
        return np.frombuffer(f.read(), dtype=dtype, count=int(header["POINTS"][0]))


def box_corners(box):
    """The 8 corners of an oriented box (centre_m, size_m, orientation_wxyz)."""
    w, x, y, z = box["orientation_wxyz"]
    rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    half = 0.5 * np.array(box["size_m"])
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return np.array(box["centre_m"]) + (signs * half) @ rotation.T


def az_el_deg(xyz):
    return (np.degrees(np.arctan2(xyz[:, 1], xyz[:, 0])),
            np.degrees(np.arctan2(xyz[:, 2], np.hypot(xyz[:, 0], xyz[:, 1]))))


# One colour per object class, for its points, its box and its label.
CLASS_COLOURS = {"drone": "#d62728", "bird": "#ff7f0e", "plane": "#9467bd", "building": "#8c564b",
                 "terrain": "#7f7f7f", "tree": "#2ca02c", "cloud": "#17becf", "background": "#bcbd22"}
FALSE_ALARM_SOURCE = 2


def range_scale(frames_points):
    """One colour scale for the whole dataset: the 1st to 99th percentile of the ranges of real
    returns in the frames drawn (false alarms, drawn at random ranges, left out)."""
    ranges = np.concatenate([p["range_m"][p["source"] != FALSE_ALARM_SOURCE].astype(float) for p in frames_points]
                            + [np.zeros(0)])
    if not len(ranges):
        return 0.0, 1.0
    lo, hi = np.percentile(ranges, [1, 99])
    return float(lo), float(max(hi, lo + 1e-3))


def draw(dataset, frames=4):
    """The preview figure of a dataset: one row per frame drawn, one colour scale for all."""
    truth = json.load(open(os.path.join(dataset, "ground_truth.json")))["frames"]
    picks = sorted(set(np.linspace(0, len(truth) - 1, min(frames, len(truth))).round().astype(int)))
    frames_points = [read_pcd(os.path.join(dataset, "frames", f"{truth[i]['index']:06d}.pcd")) for i in picks]
    norm = matplotlib.colors.Normalize(*range_scale(frames_points))
    fig, axes = plt.subplots(len(picks), 2, figsize=(13, 3.2 * len(picks)), squeeze=False,
                             gridspec_kw={"width_ratios": [2.2, 1]})
    scatter = None
    for row, index, points in zip(axes, picks, frames_points):
        frame = truth[index]
        xyz = np.stack([points["x"], points["y"], points["z"]], axis=1).astype(float)
        az, el = az_el_deg(xyz)
        whole, close = row
        real = points["source"] != FALSE_ALARM_SOURCE
        scatter = whole.scatter(az[real], el[real], c=points["range_m"][real], s=3, cmap="viridis", norm=norm,
                                linewidths=0)
        whole.scatter(az[~real], el[~real], s=3, c="lightgrey", linewidths=0, label="false alarms")
        whole.set_title(f"frame {frame['index']}: {len(points)} returns ({int((~real).sum())} false alarms, grey)")
        whole.set_xlabel("azimuth (deg, left positive)")
        whole.set_ylabel("elevation (deg)")
        # The field (the beams' own angles of real returns), not every box nor false alarm: an
        # aircraft passing beside the field would shrink it to a dot.
        if real.any():
            beam_az = np.degrees(points["beam_az"][real].astype(float))
            beam_el = np.degrees(points["beam_el"][real].astype(float))
            pad = 0.02 * max(np.ptp(beam_az), np.ptp(beam_el), 0.5)
            whole.set_xlim(beam_az.max() + pad, beam_az.min() - pad)
            whole.set_ylim(beam_el.min() - pad, beam_el.max() + pad)
        else:
            whole.invert_xaxis()
        close_done = False
        for obj in frame["objects"]:
            colour = CLASS_COLOURS.get(obj["class"], "black")
            on = points["object_id"] == obj["id"]
            if obj["class"] in ("drone", "bird", "plane"):
                whole.scatter(az[on], el[on], s=10, c=colour, linewidths=0)
            corners = box_corners(obj["box_sensor"])
            caz, cel = az_el_deg(corners)
            if not obj["returns"] and obj["class"] not in ("drone", "bird", "plane"):
                continue  # a static object out of this frame's field: no clutter
            whole.add_patch(plt.Rectangle((caz.min(), cel.min()), caz.max() - caz.min(), cel.max() - cel.min(),
                                          fill=False, edgecolor=colour, linewidth=1.5))
            whole.annotate(f"{obj['class']} {obj['id']}: {obj['returns']} returns", (caz.min(), cel.max()),
                           color=colour, fontsize=9, fontweight="bold", xytext=(4, 6), textcoords="offset points",
                           annotation_clip=True,
                           bbox={"boxstyle": "round,pad=0.2", "facecolor": "white", "edgecolor": colour, "alpha": 0.85})
            # Close-up of the first drone: cross-range metres about its box centre, along the line of sight.
            if close_done or obj["class"] != "drone":
                continue
            close_done = True
            centre = np.array(obj["box_sensor"]["centre_m"])
            sight = centre / np.linalg.norm(centre)
            left = np.cross([0.0, 0.0, 1.0], sight)
            left /= np.linalg.norm(left)
            up = np.cross(sight, left)
            near = np.abs((xyz - centre) @ sight) < 5.0
            rel = xyz[near] - centre
            close.scatter(rel @ left, rel @ up, s=14, c=np.where(on[near], colour, "grey"), linewidths=0)
            box = (corners - centre)
            close.add_patch(plt.Rectangle(((box @ left).min(), (box @ up).min()), np.ptp(box @ left),
                                          np.ptp(box @ up), fill=False, edgecolor=colour, linewidth=1.5))
            close.set_title(f"{obj['class']} {obj['id']} at {np.linalg.norm(centre):.0f} m "
                            f"(points within 5 m in range)", fontsize=9)
        close.set_xlabel("cross-range left (m)")
        close.set_ylabel("up (m)")
        close.set_aspect("equal")
        close.set_xlim(1.0, -1.0)
        close.set_ylim(-0.6, 0.6)
    fig.tight_layout()
    # One colour bar for every frame, right of the figure.
    fig.subplots_adjust(right=0.9)
    bar = fig.add_axes([0.92, 0.1, 0.015, 0.8])
    fig.colorbar(scatter, cax=bar, label="range (m), every frame")
    return fig


OWNED_LIST = ".ladarsim-owned"  # what ladarsim wrote in a dataset: see README, "Using it"


def owned_entries(directory):
    """The entries a dataset's owned list names, or None when the directory has none."""
    try:
        with open(os.path.join(directory, OWNED_LIST)) as f:
            return [line.rstrip("\n") for line in f if line.strip() and not line.startswith("#")]
    except FileNotFoundError:
        return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dataset")
    parser.add_argument("--frames", type=int, default=4, help="frames to draw, evenly spaced (default 4)")
    parser.add_argument("--force", action="store_true", help="replace DIR/preview.png even if ladarsim did not write it")
    args = parser.parse_args()
    dataset = args.dataset
    # One line in the user's terms, never a traceback.
    if not os.path.isdir(dataset):
        sys.exit(f"error: {dataset}: no such dataset directory")
    if not os.path.exists(os.path.join(dataset, "ground_truth.json")):
        sys.exit(f"error: {dataset}: no ground_truth.json: preview draws a rendered dataset (a recorded one has no "
                 "ground truth; `ladarsim view` shows it)")
    out = os.path.join(dataset, "preview.png")
    owned = owned_entries(dataset)
    if os.path.exists(out) and not args.force and (owned is None or "preview.png" not in owned):
        sys.exit(f"error: {out}: exists and ladarsim did not write it; refusing to replace it (--force replaces it)")
    if not os.access(dataset, os.W_OK):
        sys.exit(f"error: {dataset}: cannot write preview.png there (the directory is read-only)")
    fig = draw(dataset, args.frames)
    tmp = out + ".tmp.png"
    try:
        fig.savefig(tmp, dpi=90)
        os.replace(tmp, out)
        if owned is not None and "preview.png" not in owned:
            listed = os.path.join(dataset, OWNED_LIST)
            with open(listed + ".tmp", "w") as f:
                f.write(open(listed).read() + "preview.png\n")
            os.replace(listed + ".tmp", listed)
    except OSError as e:
        sys.exit(f"error: {e.filename or out}: cannot write: {e.strerror}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
