#!/usr/bin/env python3
"""Reads a KITTI export as third-party KITTI tools do and checks it against the ladarsim dataset it
came from, read with a PCD parser of its own (nothing shared with ladarsim's C++ readers).

Usage: check_kitti_export.py DATASET_DIR KITTI_DIR
Prints one line per failed check and exits 1 if any failed.

As KITTI readers: velodyne points are float32 x y z reflectance (np.fromfile(..).reshape(-1, 4)
with struct here, numpy not being assumed); labels are 15 whitespace-separated fields; a label box
is made of its corners as the devkit's compute_box_3d does (roty(ry) times l/2, 0..-h, w/2
offsets, plus the location) and taken back to the velodyne frame with inv(Tr_velo_to_cam) and
inv(R0_rect) from calib, as the devkits' project_rect_to_velo does.
"""
import glob
import json
import math
import os
import struct
import sys

failures = []


def fail(message):
    failures.append(message)


# ---------- an independent PCD reader (binary, as ladarsim's frames are) ----------

PCD_TYPES = {("F", 4): "f", ("F", 8): "d", ("U", 1): "B", ("U", 2): "H", ("U", 4): "I",
             ("I", 1): "b", ("I", 2): "h", ("I", 4): "i"}


def read_pcd(path):
    """The points of a binary PCD as a list of {field: value} dicts."""
    with open(path, "rb") as f:
        data = f.read()
    header = {}
    offset = 0
    while True:
        end = data.index(b"\n", offset)
        line = data[offset:end].decode("ascii").strip()
        offset = end + 1
        if not line or line.startswith("#"):
            continue
        key, *values = line.split()
        header[key] = values
        if key == "DATA":
            break
    assert header["DATA"] == ["binary"], f"{path}: DATA {header['DATA']}"
    fields = header["FIELDS"]
    layout = "<" + "".join(PCD_TYPES[(t, int(s))] * int(c)
                           for t, s, c in zip(header["TYPE"], header["SIZE"], header["COUNT"]))
    size = struct.calcsize(layout)
    points = int(header["POINTS"][0])
    return [dict(zip(fields, struct.unpack_from(layout, data, offset + i * size))) for i in range(points)]


# ---------- KITTI, as its readers do it ----------

def read_velodyne(path):
    with open(path, "rb") as f:
        data = f.read()
    if len(data) % 16:
        fail(f"{path}: {len(data)} bytes is not a whole number of 4-float points")
    return [struct.unpack_from("<4f", data, i) for i in range(0, len(data) - len(data) % 16, 16)]


def read_calib(path):
    calib = {}
    with open(path) as f:
        for line in f:
            if line.strip():
                key, values = line.split(":", 1)
                calib[key] = [float(v) for v in values.split()]
    return calib


def read_labels(path):
    labels = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if len(fields) != 15:
                fail(f"{path}: a label with {len(fields)} fields, not 15: {line!r}")
                continue
            v = [float(x) for x in fields[1:]]
            labels.append({"type": fields[0], "truncated": v[0], "occluded": int(fields[2]), "alpha": v[2],
                           "bbox": v[3:7], "h": v[7], "w": v[8], "l": v[9], "location": v[10:13], "ry": v[13]})
    return labels


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(len(b))) for j in range(len(b[0]))] for i in range(len(a))]


def mat_vec(a, v):
    return [sum(a[i][k] * v[k] for k in range(len(v))) for i in range(len(a))]


def inverse(m):
    """Gauss-Jordan with partial pivoting (np.linalg.inv in the devkits)."""
    n = len(m)
    a = [row[:] + [1.0 if i == j else 0.0 for j in range(n)] for i, row in enumerate(m)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        pivot = a[c][c]
        a[c] = [x / pivot for x in a[c]]
        for r in range(n):
            if r != c:
                factor = a[r][c]
                a[r] = [x - factor * y for x, y in zip(a[r], a[c])]
    return [row[n:] for row in a]


def to_4x4(values, rows, cols):
    m = [[values[r * cols + c] if c < cols else 0.0 for c in range(4)] for r in range(rows)]
    while len(m) < 4:
        m.append([0.0] * 4)
    for i in range(rows, 4):
        m[i][i] = 1.0
    if cols == 3:
        m[3][3] = 1.0
    return m


def velo_from_rect(calib):
    return mat_mul(inverse(to_4x4(calib["Tr_velo_to_cam"], 3, 4)), inverse(to_4x4(calib["R0_rect"], 3, 3)))


def label_corners_velo(label, velo_from_rect_m):
    """compute_box_3d of the KITTI devkit, then rect -> velo."""
    l, w, h, ry = label["l"], label["w"], label["h"], label["ry"]
    xs = [l / 2, l / 2, -l / 2, -l / 2, l / 2, l / 2, -l / 2, -l / 2]
    ys = [0, 0, 0, 0, -h, -h, -h, -h]
    zs = [w / 2, -w / 2, -w / 2, w / 2, w / 2, -w / 2, -w / 2, w / 2]
    c, s = math.cos(ry), math.sin(ry)
    x0, y0, z0 = label["location"]
    corners = []
    for x, y, z in zip(xs, ys, zs):
        rect = [c * x + s * z + x0, y + y0, -s * x + c * z + z0, 1.0]
        corners.append(mat_vec(velo_from_rect_m, rect)[:3])
    return corners


# ---------- ground truth boxes, from ladarsim's JSON ----------

def quaternion_matrix(w, x, y, z):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def truth_corners(box):
    r = quaternion_matrix(*box["orientation_wxyz"])
    sx, sy, sz = box["size_m"]
    corners = []
    for a in (-0.5, 0.5):
        for b in (-0.5, 0.5):
            for c in (-0.5, 0.5):
                local = [a * sx, b * sy, c * sz]
                corners.append([box["centre_m"][i] + sum(r[i][k] * local[k] for k in range(3)) for i in range(3)])
    return corners


def box_frame(corners):
    """Centre and unit axes (length, width, height) with half extents of a devkit-ordered box."""
    centre = [sum(p[i] for p in corners) / 8 for i in range(3)]
    axes = []
    for a, b in ((0, 3), (0, 1), (0, 4)):  # +l/2 vs -l/2, +w/2 vs -w/2, bottom vs top
        d = [corners[a][i] - corners[b][i] for i in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        axes.append(([x / n for x in d], n / 2))
    return centre, axes


def local_coordinates(point, frame):
    centre, axes = frame
    d = [point[i] - centre[i] for i in range(3)]
    return [(sum(d[i] * axis[i] for i in range(3)), half) for axis, half in axes]


def main(dataset_dir, kitti_dir):
    record = json.load(open(os.path.join(kitti_dir, "ladarsim_export.json")))
    truth = {f["index"]: f["objects"] for f in json.load(open(os.path.join(dataset_dir, "ground_truth.json")))["frames"]}
    pcds = sorted(glob.glob(os.path.join(dataset_dir, "frames", "*.pcd")))
    frames = [read_pcd(p) for p in pcds]
    scale = record["intensity"]["scale"]
    largest = max(p["intensity"] for f in frames for p in f)
    if not math.isclose(scale, largest, rel_tol=1e-6):
        fail(f"intensity scale {scale} is not the dataset's largest intensity {largest}")
    if len(glob.glob(os.path.join(kitti_dir, "training", "velodyne", "*.bin"))) != len(pcds):
        fail("not one velodyne file per frame")
    if os.path.exists(os.path.join(kitti_dir, "training", "image_2")):
        fail("an image_2 directory without a camera")
    checked_boxes = checked_returns = 0
    for n, (pcd, points) in enumerate(zip(pcds, frames)):
        stem = f"{n:06d}"
        entry = record["frames"][n]
        if entry["kitti"] != stem or entry["pcd"] != "frames/" + os.path.basename(pcd):
            fail(f"frame map {entry} for {pcd}")
        velo = read_velodyne(os.path.join(kitti_dir, "training", "velodyne", stem + ".bin"))
        if len(velo) != len(points):
            fail(f"{stem}.bin: {len(velo)} points, {pcd} has {len(points)} returns")
            continue
        # The documented rotation from ladarsim's sensor frame (x forward, y left, z up) to KITTI's
        # velodyne frame (the same axes) is the identity: float32 values must come through unchanged.
        for i, (v, p) in enumerate(zip(velo, points)):
            if (v[0], v[1], v[2]) != (p["x"], p["y"], p["z"]):
                fail(f"{stem}.bin point {i}: {v[:3]} is not the PCD's {(p['x'], p['y'], p['z'])}")
                break
            if not math.isclose(v[3], max(0.0, p["intensity"] / scale), rel_tol=1e-6, abs_tol=1e-12) or not 0 <= v[3] <= 1:
                fail(f"{stem}.bin point {i}: intensity {v[3]}, expected {p['intensity']} / {scale}")
                break

        calib = read_calib(os.path.join(kitti_dir, "training", "calib", stem + ".txt"))
        for key, count in (("P0", 12), ("P1", 12), ("P2", 12), ("P3", 12), ("R0_rect", 9), ("Tr_velo_to_cam", 12), ("Tr_imu_to_velo", 12)):
            if len(calib.get(key, [])) != count:
                fail(f"calib/{stem}.txt: {key} has not {count} values")
        to_velo = velo_from_rect(calib)
        labels = read_labels(os.path.join(kitti_dir, "training", "label_2", stem + ".txt"))

        returns_of = {}
        for p in points:
            returns_of.setdefault(p["object_id"], []).append((p["x"], p["y"], p["z"]))
        expected = [o for o in truth[entry["frame_index"]]
                    if o["class"] in ("drone", "bird", "plane") and returns_of.get(o["id"])]
        if len(labels) != len(expected):
            fail(f"label_2/{stem}.txt: {len(labels)} labels, expected {len(expected)} "
                 f"({[o['name'] for o in expected]})")
        for o in expected:
            centre = o["box_sensor"]["centre_m"]
            match = None
            for label in labels:
                corners = label_corners_velo(label, to_velo)
                c = [sum(p[i] for p in corners) / 8 for i in range(3)]
                if math.dist(c, centre) < 1e-4:
                    match = (label, corners)
            if match is None:
                fail(f"label_2/{stem}.txt: no box centred on {o['name']}'s ground-truth centre {centre}")
                continue
            label, corners = match
            if label["type"] != o["class"].capitalize():
                fail(f"label_2/{stem}.txt: {o['name']} labelled {label['type']}")
            if label["bbox"] != [-1, -1, -1, -1] or label["occluded"] != 3 or label["truncated"] != 0:
                fail(f"label_2/{stem}.txt: {o['name']}: no camera, yet bbox/occluded/truncated {label}")
            loc = label["location"]
            if not math.isclose(label["alpha"], math.remainder(label["ry"] - math.atan2(loc[0], loc[2]), 2 * math.pi), abs_tol=1e-5):
                fail(f"label_2/{stem}.txt: {o['name']}: alpha {label['alpha']} is not ry - atan2(x, z)")
            frame = box_frame(corners)
            # The label box holds ground truth's box: every corner inside, each face touching one.
            gt = truth_corners(o["box_sensor"])
            local = [local_coordinates(p, frame) for p in gt]
            if any(abs(u) > half + 1e-4 for pt in local for u, half in pt):
                fail(f"label_2/{stem}.txt: {o['name']}: a ground-truth corner lies outside the label box")
            for k in range(3):
                if min(half - abs(pt[k][0]) for pt in local for half in [pt[k][1]]) > 1e-4:
                    fail(f"label_2/{stem}.txt: {o['name']}: the label box is larger than ground truth's along axis {k}")
            # A box turned about the vertical only comes through unchanged: the same eight corners.
            r = quaternion_matrix(*o["box_sensor"]["orientation_wxyz"])
            if abs(r[2][2] - 1) < 1e-9 and any(min(math.dist(g, c) for c in corners) > 1e-4 for g in gt):
                fail(f"label_2/{stem}.txt: {o['name']}: a yaw-only box whose corners differ from ground truth's")
            # Returns of a still object lie in its box (range noise aside).
            if o["class"] != "drone":
                outside = [p for p in returns_of[o["id"]]
                           if any(abs(u) > half + 0.05 for u, half in local_coordinates(p, frame))]
                if outside:
                    fail(f"label_2/{stem}.txt: {o['name']}: {len(outside)} of its returns outside its box, e.g. {outside[0]}")
                checked_returns += len(returns_of[o["id"]])
            checked_boxes += 1
    print(f"checked {len(pcds)} frames, {checked_boxes} boxes, {checked_returns} returns in boxes")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
