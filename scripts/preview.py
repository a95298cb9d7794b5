#!/usr/bin/python3
"""Draws a rendered dataset's frames with their ground-truth boxes into DIR/preview.png.

Usage: preview.py DATASET_DIR [--frames N]

Each row is one frame: left, the whole field in azimuth/elevation, points coloured by range;
right, a close-up of each target's box (cross-range metres about its centre) with the points that
hit it. Reads only the files a user gets (binary PCD frames and ground_truth.json).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dataset")
    parser.add_argument("--frames", type=int, default=4, help="frames to draw, evenly spaced (default 4)")
    args = parser.parse_args()

    truth = json.load(open(os.path.join(args.dataset, "ground_truth.json")))["frames"]
    targets = {"drone", "bird", "plane"}
    picks = sorted(set(np.linspace(0, len(truth) - 1, min(args.frames, len(truth))).round().astype(int)))
    fig, axes = plt.subplots(len(picks), 2, figsize=(13, 3.2 * len(picks)), squeeze=False,
                             gridspec_kw={"width_ratios": [2.2, 1]})
    for row, index in zip(axes, picks):
        frame = truth[index]
        points = read_pcd(os.path.join(args.dataset, "frames", f"{frame['index']:06d}.pcd"))
        xyz = np.stack([points["x"], points["y"], points["z"]], axis=1).astype(float)
        az, el = az_el_deg(xyz)
        whole, close = row
        scatter = whole.scatter(az, el, c=points["range_m"], s=3, cmap="viridis", linewidths=0)
        fig.colorbar(scatter, ax=whole, label="range (m)")
        whole.set_title(f"frame {frame['index']}: {len(points)} returns")
        whole.set_xlabel("azimuth (deg, left positive)")
        whole.set_ylabel("elevation (deg)")
        whole.invert_xaxis()
        # The field (the beams' own angles), not every box: an aircraft passing beside the field
        # would shrink it to a dot.
        if len(points):
            beam_az, beam_el = np.degrees(points["beam_az"].astype(float)), np.degrees(points["beam_el"].astype(float))
            pad = 0.02 * max(np.ptp(beam_az), np.ptp(beam_el), 0.5)
            whole.set_xlim(beam_az.max() + pad, beam_az.min() - pad)
            whole.set_ylim(beam_el.min() - pad, beam_el.max() + pad)
        close_done = False
        for obj in frame["objects"]:
            if obj["class"] not in targets:
                continue
            on = points["object_id"] == obj["id"]
            whole.scatter(az[on], el[on], s=10, c="red", linewidths=0)
            corners = box_corners(obj["box_sensor"])
            caz, cel = az_el_deg(corners)
            whole.add_patch(plt.Rectangle((caz.min(), cel.min()), caz.max() - caz.min(), cel.max() - cel.min(),
                                          fill=False, edgecolor="red", linewidth=1.5))
            whole.annotate(f"{obj['class']} {obj['id']}: {obj['returns']} returns",
                           (caz.min(), cel.max()), color="red", fontsize=8,
                           xytext=(4, 6), textcoords="offset points")
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
            close.scatter(rel @ left, rel @ up, s=14, c=np.where(on[near], "red", "grey"), linewidths=0)
            box = (corners - centre)
            close.add_patch(plt.Rectangle(((box @ left).min(), (box @ up).min()), np.ptp(box @ left),
                                          np.ptp(box @ up), fill=False, edgecolor="red", linewidth=1.5))
            close.set_title(f"{obj['class']} {obj['id']} at {np.linalg.norm(centre):.0f} m "
                            f"(points within 5 m in range)", fontsize=9)
        close.set_xlabel("cross-range left (m)")
        close.set_ylabel("up (m)")
        close.set_aspect("equal")
        close.set_xlim(1.0, -1.0)
        close.set_ylim(-0.6, 0.6)
    fig.tight_layout()
    out = os.path.join(args.dataset, "preview.png")
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=90)
    os.replace(tmp, out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
