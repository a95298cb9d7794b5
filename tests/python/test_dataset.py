"""ladarsim.Dataset: a rendered dataset and a recorded VLP-16 capture read lazily, their frames
equal to what our own PCD reader finds in the files."""
import numpy as np
import pytest

import ladarsim
from conftest import SHARED_DIR, SMALL, read_json, run_cli
from pcd_numpy import read_pcd

VLP16_CAPTURE = SHARED_DIR / "data" / "vlp16" / "velodyne_vlp16.pcap"


def test_a_rendered_dataset_reads_as_its_files(cli_small):
    dataset = ladarsim.Dataset(cli_small)
    assert len(dataset) == 3
    manifest = read_json(cli_small / "manifest.json")
    assert dataset.manifest == manifest
    assert dataset.sensor == manifest["sensor"]
    assert dataset.background.tobytes() == read_pcd(cli_small / "background.pcd").tobytes()
    truth = read_json(cli_small / "ground_truth.json")["frames"]
    frames = list(dataset)
    assert [f.index for f in frames] == [0, 1, 2]
    for k, frame in enumerate(frames):
        expected = read_pcd(cli_small / "frames" / f"{k:06d}.pcd")
        assert frame.points.dtype == expected.dtype
        assert frame.points.tobytes() == expected.tobytes()
        assert frame.ground_truth == truth[k]["objects"]
        assert frame.start_time_s == manifest["frames"][k]["start_time_s"]
        assert frame.gimbal_az_rad == manifest["frames"][k]["gimbal_az_rad"]
        assert frame.range_image["range_m"].shape == (20, 150)
    assert dataset[-1].points.tobytes() == frames[2].points.tobytes()
    assert [f.index for f in dataset[1:]] == [1, 2]
    with pytest.raises(IndexError):
        dataset[3]


def test_a_directory_that_is_no_dataset_is_an_input_error(tmp_path):
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.Dataset(tmp_path)
    assert error.value.field == "frames" and error.value.file == str(tmp_path)


@pytest.mark.skipif(not VLP16_CAPTURE.exists(), reason=f"shared data absent: {VLP16_CAPTURE}")
def test_an_imported_vlp16_capture_reads_as_recorded_frames(tmp_path):
    out = tmp_path / "vlp16"
    run_cli("import-velodyne", VLP16_CAPTURE, "--out", out)
    dataset = ladarsim.Dataset(out)
    files = sorted((out / "frames").glob("*.pcd"))
    assert len(dataset) == len(files) > 0
    assert dataset.sensor["name"] == "velodyne_vlp16"
    assert ladarsim.Sensor.from_document(dataset.sensor).rows == 16
    assert dataset.background is None
    records = {r["index"]: r for r in dataset.manifest["frames"]}
    spans = []
    for frame, file in zip(dataset, files):
        expected = read_pcd(file)
        assert frame.points.tobytes() == expected.tobytes()
        assert len(frame.points) == records[frame.index]["returns"] > 0
        assert frame.range_image is None and frame.ground_truth is None
        assert frame.start_time_s == records[frame.index]["start_time_s"] <= frame.end_time_s
        assert set(np.unique(frame.points["row"])) <= set(range(16))
        azimuth = np.degrees(np.arctan2(frame.points["y"], frame.points["x"]))
        spans.append(azimuth.max() - azimuth.min())
    # The capture starts mid-revolution; a whole one has points all around the sensor.
    assert max(spans) > 355


def test_a_frames_pose_takes_its_points_to_the_world(cli_small):
    """poses.txt read as each frame's 4 x 4 world-from-sensor matrix: the scenario's mount (its
    position_m and yaw_deg, composed here by hand), the same for a frame rendered in memory."""
    scenario = read_json(ladarsim.Dataset(cli_small).manifest["scenario_file"])
    sensor = scenario["sensor"]
    yaw = np.radians(sensor.get("yaw_deg", 0.0))
    assert sensor.get("pitch_deg", 0.0) == 0.0 and sensor.get("roll_deg", 0.0) == 0.0
    expected = np.eye(4)
    expected[:2, :2] = [[np.cos(yaw), -np.sin(yaw)], [np.sin(yaw), np.cos(yaw)]]
    expected[:3, 3] = sensor["position_m"]
    lines = (cli_small / "poses.txt").read_text().splitlines()
    dataset = ladarsim.Dataset(cli_small)
    assert len(lines) == len(dataset)
    for frame, line in zip(dataset, lines):
        assert frame.pose.shape == (4, 4)
        assert np.allclose(frame.pose, expected, atol=1e-12)
        assert np.array_equal(frame.pose[:3].ravel(), np.array(line.split(), dtype=float))
    rendered = next(iter(ladarsim.render(SMALL, frames=1)))
    assert np.array_equal(rendered.pose, dataset[0].pose)
