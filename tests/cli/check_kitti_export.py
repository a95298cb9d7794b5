#!/usr/bin/python3
"""Reads a KITTI export as third-party KITTI tools do and checks it against the ladarsim dataset it
came from, read with the tests' own PCD reader (tests/python/pcd_numpy.py, nothing of ladarsim's).

Usage: check_kitti_export.py DATASET_DIR KITTI_DIR
Prints one line per failed check and exits 1 if any failed.

As KITTI readers do: velodyne points by np.fromfile(path, dtype=np.float32).reshape(-1, 4); labels
as 15 whitespace-separated fields; a label's box from its corners as the devkit's compute_box_3d
builds them (roty(ry) times the l/2, 0..-h, w/2 offsets, plus the location), taken back to the
velodyne frame with inv(Tr_velo_to_cam) @ inv(R0_rect) from calib, as project_rect_to_velo does.
Points in a box as OpenPCDet counts them (points_in_boxes: strictly inside each half extent).

The exact box ladarsim_export.json keeps for each label must be ground truth's; the label's own
box (docs/kitti.md, "Labels") must hold ground truth's box and every one of the object's returns,
and be no larger than the tightest such box plus the documented margin, unless the export was
made with --exact-boxes, whose labels are the exact boxes.
"""
import glob
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from pcd_numpy import read_pcd  # noqa: E402

failures = []


def fail(message):
    failures.append(message)


def read_calib(path):
    calib = {}
    with open(path) as f:
        for line in f:
            if line.strip():
                key, values = line.split(":", 1)
                calib[key] = np.array([float(v) for v in values.split()])
    return calib


def parse_label(line, where):
    fields = line.split()
    if len(fields) != 15:
        fail(f"{where}: a label with {len(fields)} fields, not 15: {line!r}")
        return None
    v = [float(x) for x in fields[1:]]
    return {"type": fields[0], "truncated": v[0], "occluded": int(fields[2]), "alpha": v[2],
            "bbox": v[3:7], "h": v[7], "w": v[8], "l": v[9], "location": np.array(v[10:13]), "ry": v[13]}


def read_labels(path):
    with open(path) as f:
        return [label for label in (parse_label(line, path) for line in f) if label is not None]


def velo_from_rect(calib):
    tr = np.eye(4)
    tr[:3, :] = calib["Tr_velo_to_cam"].reshape(3, 4)
    r0 = np.eye(4)
    r0[:3, :3] = calib["R0_rect"].reshape(3, 3)
    return np.linalg.inv(tr) @ np.linalg.inv(r0)


def label_corners_velo(label, velo_from_rect_m):
    """compute_box_3d of the KITTI devkit, then rect -> velo: 8 x 3."""
    l, w, h, ry = label["l"], label["w"], label["h"], label["ry"]
    corners = np.array([[l / 2, l / 2, -l / 2, -l / 2, l / 2, l / 2, -l / 2, -l / 2],
                        [0, 0, 0, 0, -h, -h, -h, -h],
                        [w / 2, -w / 2, -w / 2, w / 2, w / 2, -w / 2, -w / 2, w / 2]])
    c, s = math.cos(ry), math.sin(ry)
    roty = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    rect = roty @ corners + label["location"].reshape(3, 1)
    return (velo_from_rect_m @ np.vstack([rect, np.ones(8)]))[:3].T


def quaternion_matrix(w, x, y, z):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def truth_corners(box):
    """Ground truth's box_sensor: 8 x 3."""
    offsets = np.array([[a, b, c] for a in (-0.5, 0.5) for b in (-0.5, 0.5) for c in (-0.5, 0.5)]) * box["size_m"]
    return np.array(box["centre_m"]) + offsets @ quaternion_matrix(*box["orientation_wxyz"]).T


def local_coordinates(points, corners):
    """Points in the frame of a devkit-ordered box, with its half extents along (l, w, h)."""
    centre = corners.mean(axis=0)
    edges = np.array([corners[0] - corners[3], corners[0] - corners[1], corners[0] - corners[4]])
    half = np.linalg.norm(edges, axis=1) / 2
    return (points - centre) @ (edges / (2 * half[:, None])).T, half


def check_frame(n, pcd, points, truth, record, kitti_dir, reach_per_m):
    stem = f"{n:06d}"
    entry = record["frames"][n]
    if entry["kitti"] != stem or entry["pcd"] != "frames/" + os.path.basename(pcd):
        fail(f"frame map {entry} for {pcd}")
    velo = np.fromfile(os.path.join(kitti_dir, "training", "velodyne", stem + ".bin"), dtype=np.float32).reshape(-1, 4)
    if len(velo) != len(points):
        fail(f"{stem}.bin: {len(velo)} points, {pcd} has {len(points)} returns")
        return 0, 0
    # The documented rotation from ladarsim's sensor frame (x forward, y left, z up) to KITTI's
    # velodyne frame (the same axes) is the identity: the float32 values come through unchanged.
    velo_from_sensor = np.eye(3, dtype=np.float32)
    xyz = np.stack([points["x"], points["y"], points["z"]], axis=1) @ velo_from_sensor.T
    if not np.array_equal(velo[:, :3], xyz):
        bad = int(np.argmax(np.any(velo[:, :3] != xyz, axis=1)))
        fail(f"{stem}.bin point {bad}: {velo[bad, :3]} is not the PCD's {xyz[bad]}")
    scale = record["intensity"]["scale"]
    expected_intensity = np.maximum(0.0, points["intensity"] / np.float32(scale))
    if not np.allclose(velo[:, 3], expected_intensity, rtol=1e-6, atol=0) or velo[:, 3].min() < 0 or velo[:, 3].max() > 1:
        fail(f"{stem}.bin: intensity is not the PCD's / {scale} within 0..1")

    calib = read_calib(os.path.join(kitti_dir, "training", "calib", stem + ".txt"))
    for key, count in (("P0", 12), ("P1", 12), ("P2", 12), ("P3", 12), ("R0_rect", 9), ("Tr_velo_to_cam", 12),
                       ("Tr_imu_to_velo", 12)):
        if len(calib.get(key, [])) != count:
            fail(f"calib/{stem}.txt: {key} has not {count} values")
    to_velo = velo_from_rect(calib)
    labels = read_labels(os.path.join(kitti_dir, "training", "label_2", stem + ".txt"))
    boxes = [label_corners_velo(label, to_velo) for label in labels]

    expected = [o for o in truth[entry["frame_index"]]
                if o["class"] in ("drone", "bird", "plane") and np.any(points["object_id"] == o["id"])]
    recorded = entry["labels"]
    if [r["id"] for r in recorded] != [o["id"] for o in expected] or len(labels) != len(expected):
        fail(f"label_2/{stem}.txt: {len(labels)} labels for objects {[r['id'] for r in recorded]}, expected "
             f"{len(expected)} ({[o['name'] for o in expected]})")
        return 0, 0
    checked_boxes = checked_returns = 0
    for o, label, corners, r in zip(expected, labels, boxes, recorded):
        what = f"label_2/{stem}.txt: {o['name']}"
        own = points["object_id"] == o["id"]
        mine = xyz[own]
        if r["returns"] != len(mine):
            fail(f"{what}: ladarsim_export.json counts {r['returns']} returns, the PCD {len(mine)}")
        exact = parse_label(r["exact_label"], f"ladarsim_export.json frame {stem}")
        if exact is None:
            continue
        for box_label, box_what in ((label, what), (exact, what + " (exact box)")):
            if box_label["type"] != o["class"].capitalize():
                fail(f"{box_what}: labelled {box_label['type']}")
            if box_label["bbox"] != [-1, -1, -1, -1] or box_label["occluded"] != 3 or box_label["truncated"] != 0:
                fail(f"{box_what}: no camera, yet bbox/occluded/truncated {box_label}")
            loc = box_label["location"]
            if abs(math.remainder(box_label["alpha"] - (box_label["ry"] - math.atan2(loc[0], loc[2])), 2 * math.pi)) > 1e-5:
                fail(f"{box_what}: alpha {box_label['alpha']} is not ry - atan2(x, z)")
        # The exact box is ground truth's: every corner inside, and a corner on each face.
        exact_corners = label_corners_velo(exact, to_velo)
        gt = truth_corners(o["box_sensor"])
        if np.linalg.norm(exact_corners.mean(axis=0) - o["box_sensor"]["centre_m"]) > 1e-4:
            fail(f"{what}: the exact box is not centred on ground truth's centre {o['box_sensor']['centre_m']}")
        local, half = local_coordinates(gt, exact_corners)
        if np.any(np.abs(local) > half + 1e-4):
            fail(f"{what}: a ground-truth corner lies outside the exact box")
        if np.any(np.min(half - np.abs(local), axis=0) > 1e-4):
            fail(f"{what}: the exact box is larger than ground truth's")
        # A box turned about the vertical only comes through unchanged: the same eight corners.
        upright = abs(quaternion_matrix(*o["box_sensor"]["orientation_wxyz"])[2, 2] - 1) < 1e-9
        if upright and np.max(np.min(np.linalg.norm(gt[:, None] - exact_corners[None], axis=2), axis=1)) > 1e-4:
            fail(f"{what}: a yaw-only box whose corners differ from ground truth's")
        # Returns of a still object lie in its exact box, up to range noise and the footprint's
        # reach: a return lies on its beam's axis, which may pass beside the object its
        # footprint's rim meets. A drone moves during a scan.
        if o["class"] != "drone":
            allowance = 0.05 + reach_per_m * points["range_m"][own]
            local, half = local_coordinates(mine, exact_corners)
            outside = int(np.sum(np.any(np.abs(local) > half + allowance[:, None], axis=1)))
            if outside:
                fail(f"{what}: {outside} of its {len(mine)} returns lie outside its exact box")
            checked_returns += len(mine)
        if record["label_boxes"] == "exact":
            if np.max(np.abs(corners - exact_corners)) > 1e-6:
                fail(f"{what}: exported with exact boxes, yet its label is not the exact box")
        else:
            # The label holds ground truth's box and, strictly inside as OpenPCDet counts points,
            # every return of the object; each face is within the margin of one of them.
            local_gt, half = local_coordinates(gt, corners)
            local_returns, _ = local_coordinates(mine.astype(np.float64), corners)
            if np.any(np.abs(local_gt) > half + 1e-4):
                fail(f"{what}: a ground-truth corner lies outside the label box")
            inside = np.all(np.abs(local_returns) < half, axis=1)
            if not np.all(inside):
                fail(f"{what}: {int(np.sum(~inside))} of its {len(mine)} returns lie outside its label box"
                     f"{' (none inside)' if not np.any(inside) else ''}")
            held = np.vstack([local_gt, local_returns])
            slack = np.maximum(np.min(half - held, axis=0), np.min(half + held, axis=0))
            if np.any(slack > record["label_margin_m"] + 1e-4):
                fail(f"{what}: the label box is {slack.max():.4f} m larger than the tightest box holding "
                     f"ground truth's and the returns, beyond the margin {record['label_margin_m']} m")
        checked_boxes += 1
    return checked_boxes, checked_returns


def main(dataset_dir, kitti_dir):
    record = json.load(open(os.path.join(kitti_dir, "ladarsim_export.json")))
    truth = {f["index"]: f["objects"] for f in json.load(open(os.path.join(dataset_dir, "ground_truth.json")))["frames"]}
    pcds = sorted(glob.glob(os.path.join(dataset_dir, "frames", "*.pcd")))
    frames = [read_pcd(p) for p in pcds]
    largest = max(float(f["intensity"].max()) for f in frames)
    if not math.isclose(record["intensity"]["scale"], largest, rel_tol=1e-6):
        fail(f"intensity scale {record['intensity']['scale']} is not the dataset's largest intensity {largest}")
    if len(glob.glob(os.path.join(kitti_dir, "training", "velodyne", "*.bin"))) != len(pcds):
        fail("not one velodyne file per frame")
    if os.path.exists(os.path.join(kitti_dir, "training", "image_2")):
        fail("an image_2 directory without a camera")
    # How far beside its axis a beam's truncated footprint reaches, per metre of range.
    manifest = json.load(open(os.path.join(dataset_dir, "manifest.json")))
    transmitter = manifest["sensor"]["transmitter"]
    divergence_mrad = max(transmitter["divergence_mrad"], transmitter.get("divergence_el_mrad", 0.0))
    reach_per_m = manifest["render"]["footprint_truncation"] * 0.5e-3 * divergence_mrad
    boxes = returns = 0
    for n, (pcd, points) in enumerate(zip(pcds, frames)):
        b, r = check_frame(n, pcd, points, truth, record, kitti_dir, reach_per_m)
        boxes, returns = boxes + b, returns + r
    print(f"checked {len(pcds)} frames, {boxes} boxes, {returns} returns in boxes")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
