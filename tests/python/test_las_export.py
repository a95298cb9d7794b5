"""`ladarsim export-las` read back by a LAS 1.4 reader of our own written from the specification
(ASPRS LAS 1.4 R15; Debian 12 has no laspy), independent of ladarsim's: every frame's LAS holds
its PCD's returns, positions and fields, in the sensor frame and, with --world, placed by the
mount's pose."""
import json
import struct
import subprocess

import numpy as np
import pytest

from conftest import CLI, SMALL, read_json, run_cli
from pcd_numpy import read_pcd

HEADER = struct.Struct("<4sHH16sBB32s32sHHHIIBHI5I3d3d6dQQIQ15Q")  # the 375-byte LAS 1.4 header
VLR = struct.Struct("<H16sHH32s")
DESCRIPTOR = struct.Struct("<2sBB32s4s8s16s8s16s8s16s8s16s8s16s32s")
EXTRA_TYPES = {5: "<u4", 9: "<f4"}
CLASS_CODES = {"background": 1, "terrain": 2, "tree": 5, "building": 6, "drone": 64, "bird": 65, "plane": 66, "cloud": 67}
NOISE = 7


def read_las(path):
    """The header fields this test checks, the extra-bytes descriptors and the points as a NumPy record array."""
    blob = path.read_bytes()
    h = HEADER.unpack_from(blob, 0)
    assert HEADER.size == 375 and h[0] == b"LASF" and (h[4], h[5]) == (1, 4)
    header = {"global_encoding": h[2], "header_size": h[10], "point_offset": h[11], "vlrs": h[12],
              "format": h[13], "record_length": h[14], "legacy_count": h[15], "scale": h[21:24],
              "offset": h[24:27], "max_min": h[27:33], "count": h[36], "by_return": h[37:52]}
    at, extra = header["header_size"], []
    for _ in range(header["vlrs"]):
        _, user, record, length, _ = VLR.unpack_from(blob, at)
        at += VLR.size
        if user.rstrip(b"\0") == b"LASF_Spec" and record == 4:
            for d in range(0, length, DESCRIPTOR.size):
                fields = DESCRIPTOR.unpack_from(blob, at + d)
                extra.append({"type": fields[1], "options": fields[2], "name": fields[3].rstrip(b"\0").decode(),
                              "no_data": fields[5]})
        at += length
    dtype = np.dtype([("X", "<i4"), ("Y", "<i4"), ("Z", "<i4"), ("intensity", "<u2"), ("returns", "u1"),
                      ("flags", "u1"), ("classification", "u1"), ("user_data", "u1"), ("scan_angle", "<i2"),
                      ("point_source", "<u2"), ("gps_time", "<f8")] +
                     [(e["name"], EXTRA_TYPES[e["type"]]) for e in extra])
    assert dtype.itemsize == header["record_length"]
    points = np.frombuffer(blob, dtype=dtype, count=header["count"], offset=header["point_offset"])
    assert len(blob) == header["point_offset"] + header["count"] * dtype.itemsize
    return header, extra, points


def positions(header, points):
    return np.stack([points[a] * header["scale"][i] + header["offset"][i] for i, a in enumerate("XYZ")], axis=1)


def quaternion_matrix(w, x, y, z):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


@pytest.fixture(scope="module")
def exports(cli_small, tmp_path_factory):
    out = tmp_path_factory.mktemp("las")
    run_cli("export-las", cli_small, "--out", out / "sensor")
    return out


@pytest.fixture(scope="module")
def turned(tmp_path_factory):
    """tests/cli/small.json's first frame from a mount turned about all three axes, exported both ways."""
    out = tmp_path_factory.mktemp("turned")
    scenario = json.loads(SMALL.read_text())
    scenario["sensor"].update({"position_m": [3, -2, 5], "yaw_deg": 25, "pitch_deg": -4, "roll_deg": 3})
    for o in scenario["objects"]:
        o["model"] = str(SMALL.parent / o["model"])
    (out / "scenario.json").write_text(json.dumps(scenario))
    run_cli("render", out / "scenario.json", "--out", out / "d", "--frames", 1, "--quiet")
    run_cli("export-las", out / "d", "--out", out / "sensor")
    run_cli("export-las", out / "d", "--out", out / "world", "--world")
    return out


def test_each_frame_s_las_holds_its_pcd_s_returns_and_fields(cli_small, exports):
    truth = read_json(cli_small / "ground_truth.json")["frames"]
    classes = {0: "background", **{o["id"]: o["class"] for f in truth for o in f["objects"]}}
    record = read_json(exports / "sensor" / "ladarsim_export.json")
    scale = record["intensity"]["scale"]
    pcds = sorted((cli_small / "frames").glob("*.pcd"))
    assert [f["las"] for f in record["frames"]] == [f"{k:06d}.las" for k in range(len(pcds))]
    largest = max(read_pcd(p)["intensity"].max() for p in pcds)
    assert scale == pytest.approx(float(largest))
    seen_classes = set()
    for k, pcd_file in enumerate(pcds):
        pcd = read_pcd(pcd_file)
        header, extra, las = read_las(exports / "sensor" / f"{k:06d}.las")
        assert header["format"] == 6 and header["legacy_count"] == 0 and header["count"] == len(pcd) > 0
        assert header["global_encoding"] & 0x10, "format 6 needs the WKT bit"
        assert [(e["name"], e["type"]) for e in extra] == [("object_id", 5), ("intensity_pe", 9)]
        assert extra[0]["options"] & 1 and struct.unpack("<Q", extra[0]["no_data"])[0] == 0xFFFFFFFF
        xyz = positions(header, las)
        pcd_xyz = np.stack([pcd["x"], pcd["y"], pcd["z"]], axis=1).astype(np.float64)
        assert np.abs(xyz - pcd_xyz).max() <= 0.5e-4 + 1e-9
        assert np.allclose(header["max_min"][0::2], xyz.max(axis=0)) and np.allclose(header["max_min"][1::2], xyz.min(axis=0))
        assert np.array_equal(las["gps_time"], pcd["time_s"])
        assert np.array_equal(las["object_id"], pcd["object_id"])
        assert np.array_equal(las["intensity_pe"], pcd["intensity"])
        expected = np.round(65535 * np.clip(pcd["intensity"].astype(np.float64) / scale, 0, 1))
        assert np.abs(las["intensity"].astype(np.float64) - expected).max() <= 1
        beams = {}
        for c, r in zip(pcd["column"], pcd["row"]):
            beams[(c, r)] = beams.get((c, r), 0) + 1
        assert np.array_equal(las["returns"] & 0x0F, pcd["return_index"].astype(np.uint8) + 1)
        assert np.array_equal(las["returns"] >> 4, [beams[(c, r)] for c, r in zip(pcd["column"], pcd["row"])])
        assert header["by_return"][0] == np.count_nonzero(pcd["return_index"] == 0)
        codes = [NOISE if s == 2 else CLASS_CODES[classes[i]] for s, i in zip(pcd["source"], pcd["object_id"])]
        assert np.array_equal(las["classification"], codes)
        assert np.array_equal(las["user_data"], pcd["source"])
        assert np.abs(las["scan_angle"] * 0.006 - np.degrees(pcd["beam_az"])).max() <= 0.003 + 1e-6
        seen_classes |= {classes[i] for i in pcd["object_id"]}
    assert {"drone", "building"} <= seen_classes, "the scenario's drone and building should both have returns"


def test_world_coordinates_are_the_sensor_frame_s_placed_by_the_mount(turned):
    mount = read_json(turned / "d" / "manifest.json")["mount"]
    rotation = quaternion_matrix(*mount["orientation_wxyz"])
    assert not np.allclose(rotation, np.eye(3)), "the mount should be turned"
    header, _, las = read_las(turned / "world" / "000000.las")
    sensor_header, _, sensor_las = read_las(turned / "sensor" / "000000.las")
    assert header["count"] == sensor_header["count"] > 0
    expected = positions(sensor_header, sensor_las) @ rotation.T + np.array(mount["position_m"])
    assert np.abs(positions(header, las) - expected).max() <= 1.5e-4
    assert read_json(turned / "world" / "ladarsim_export.json")["frame"].startswith("world")


def test_a_user_s_file_is_kept_and_bad_input_refused_in_one_line(cli_small, tmp_path):
    out = tmp_path / "las"
    run_cli("export-las", cli_small, "--out", out)
    (out / "NOTES.txt").write_text("mine")
    assert "NOTES.txt" in run_cli("export-las", cli_small, "--out", out)
    assert (out / "NOTES.txt").read_text() == "mine" and (out / "000000.las").exists()
    (tmp_path / "plain").mkdir()
    (tmp_path / "plain" / "000000.las").write_text("not ladarsim's")
    for args, word in [([tmp_path / "none", "--out", tmp_path / "x"], "no such directory"),
                       ([cli_small, "--out", tmp_path / "plain"], "--out")]:
        result = subprocess.run([str(CLI), "export-las", *map(str, args)], capture_output=True, text=True)
        assert result.returncode == 2 and word in result.stderr and len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert (tmp_path / "plain" / "000000.las").read_text() == "not ladarsim's"


def test_world_coordinates_of_a_moving_platform_are_each_return_placed_by_the_pose_at_its_time(tmp_path):
    """tests/cli/small.json from a platform driving at 20 m/s along x and yawing 3 deg at 2 Hz: the
    world LAS must hold each sensor-frame return moved by the platform's pose at that return's own
    time, computed here from the scenario alone (a frame's start pose would be off by metres)."""
    scenario = json.loads(SMALL.read_text())
    start, velocity, amplitude, frequency, phase = np.array([0.0, 0.0, 2.0]), np.array([20.0, 0.0, 0.0]), 3.0, 2.0, 30.0
    del scenario["sensor"]["position_m"]
    scenario["sensor"]["trajectory"] = {"type": "straight", "start_m": start.tolist(), "velocity_mps": velocity.tolist()}
    scenario["sensor"]["sway"] = {"components": [{"axis": "yaw", "amplitude_deg": amplitude, "frequency_hz": frequency,
                                                  "phase_deg": phase}]}
    for o in scenario["objects"]:
        o["model"] = str(SMALL.parent / o["model"])
    (tmp_path / "scenario.json").write_text(json.dumps(scenario))
    run_cli("render", tmp_path / "scenario.json", "--out", tmp_path / "d", "--quiet")
    run_cli("export-las", tmp_path / "d", "--out", tmp_path / "sensor")
    run_cli("export-las", tmp_path / "d", "--out", tmp_path / "world", "--world")
    # Allowed: the two files' 0.1 mm quantisation (a rotated sensor-frame coordinate mixes two) and
    # the slerp between the trajectory's 1 ms samples, within (2 pi f)^2 A dt^2 / 8 of the true angle
    # (docs/scenario.md), times the return's range.
    angle_bound = (2 * np.pi * frequency) ** 2 * np.radians(amplitude) * 1e-3 ** 2 / 8
    worst, worst_frame_start = 0.0, 0.0
    for k in range(scenario["render"]["frames"]):
        header, _, las = read_las(tmp_path / "world" / f"{k:06d}.las")
        sensor_header, _, sensor_las = read_las(tmp_path / "sensor" / f"{k:06d}.las")
        assert header["count"] == sensor_header["count"] > 0
        p = positions(sensor_header, sensor_las)
        t = sensor_las["gps_time"]
        yaw = np.radians(amplitude * np.sin(2 * np.pi * frequency * t + np.radians(phase)))
        c, s = np.cos(yaw), np.sin(yaw)
        expected = np.stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1], p[:, 2]], axis=1)
        expected += start + np.outer(t, velocity)
        allowed = (np.sqrt(2) + 1) * 0.5e-4 + angle_bound * np.linalg.norm(p, axis=1) + 1e-9
        worst = max(worst, (np.abs(positions(header, las) - expected).max(axis=1) / allowed).max())
        t0 = np.full_like(t, t.min())
        yaw0 = np.radians(amplitude * np.sin(2 * np.pi * frequency * t0 + np.radians(phase)))
        at_start = np.stack([np.cos(yaw0) * p[:, 0] - np.sin(yaw0) * p[:, 1], np.sin(yaw0) * p[:, 0] + np.cos(yaw0) * p[:, 1],
                             p[:, 2]], axis=1) + start + np.outer(t0, velocity)
        worst_frame_start = max(worst_frame_start, np.abs(positions(header, las) - at_start).max())
    assert worst <= 1.0, f"a return is {worst:.2f} times the allowed distance from where the pose at its time puts it"
    assert worst_frame_start > 0.1, "the platform should move enough in a frame for the check to tell the poses apart"
