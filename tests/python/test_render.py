"""ladarsim.render: frames equal, value for value, to the files `ladarsim render` writes for the
same scenario and seed (read with our own PCD reader), a dict scenario read as its file would be,
and render(out=DIR) writing exactly what the command line writes."""
import filecmp
import os
import pathlib
import threading
import time

import numpy as np
import pytest

import ladarsim
from conftest import SMALL, read_json, run_cli
from pcd_numpy import read_pcd


def small_document():
    return read_json(SMALL)


def test_frames_equal_the_command_lines_files(cli_small):
    truth = read_json(cli_small / "ground_truth.json")["frames"]
    stream = ladarsim.render(SMALL, threads=1)  # the command line used 2: output does not depend on it
    assert len(stream) == 3
    count = 0
    for k, frame in enumerate(stream):
        count += 1
        assert frame.index == k
        expected = read_pcd(cli_small / "frames" / f"{k:06d}.pcd")
        assert frame.points.dtype == expected.dtype  # names, types, packing
        assert len(frame.points) == len(expected) > 0
        for name in expected.dtype.names:
            assert np.array_equal(frame.points[name], expected[name]), name
        assert frame.points.tobytes() == expected.tobytes()
        # The ground truth as ground_truth.json holds the frame's objects, with its times.
        assert frame.ground_truth == truth[k]["objects"]
        assert (frame.start_time_s, frame.end_time_s) == (truth[k]["start_time_s"], truth[k]["end_time_s"])
        assert frame.time_s == 0.5 * (truth[k]["start_time_s"] + truth[k]["end_time_s"])
    assert count == 3


def test_range_image_holds_each_beams_first_return_as_the_exr_does(cli_small):
    frame = next(iter(ladarsim.render(SMALL, frames=1)))
    image = frame.range_image
    assert sorted(image) == ["Y", "intensity", "object_id", "range_m", "strongest_intensity", "strongest_range_m"]
    rows, columns = image["range_m"].shape
    assert (columns, rows) == (150, 20)
    assert image["range_m"].dtype == np.float32 and image["object_id"].dtype == np.uint32
    # Independently from the points: the first return of each beam at (row, column).
    first = frame.points[frame.points["return_index"] == 0]
    expected = np.zeros((rows, columns), np.float32)
    expected[first["row"], first["column"]] = first["range_m"].astype(np.float32)
    assert np.array_equal(image["range_m"], expected)
    assert np.array_equal(image["Y"], expected)
    ids = np.full((rows, columns), 0xFFFFFFFE, np.uint32)  # an empty pixel, unlike a false alarm
    ids[first["row"], first["column"]] = first["object_id"]
    assert np.array_equal(image["object_id"], ids)
    strongest = np.zeros((rows, columns), np.float32)
    brightest = np.zeros((rows, columns), np.float32)
    for p in frame.points:
        if p["intensity"] > brightest[p["row"], p["column"]] or strongest[p["row"], p["column"]] == 0:
            brightest[p["row"], p["column"]] = p["intensity"]
            strongest[p["row"], p["column"]] = np.float32(p["range_m"])
    assert np.array_equal(image["strongest_range_m"], strongest)
    assert np.array_equal(image["strongest_intensity"], brightest)
    # And as the command line's EXR holds it (read back through the module).
    on_disk = ladarsim.Dataset(cli_small)[0].range_image
    for name in image:
        assert np.array_equal(image[name], on_disk[name]), name


def test_a_dict_scenario_reads_its_paths_from_base_dir_and_renders_as_its_file():
    from_file = next(iter(ladarsim.render(SMALL, frames=1, seed=3)))
    from_dict = next(iter(ladarsim.render(small_document(), frames=1, seed=3, base_dir=SMALL.parent)))
    assert from_dict.points.tobytes() == from_file.points.tobytes()
    assert from_dict.ground_truth == from_file.ground_truth
    # A different seed gives different noise: the override reaches the renderer.
    other = next(iter(ladarsim.render(SMALL, frames=1, seed=4)))
    assert other.points.tobytes() != from_file.points.tobytes()


def test_a_typo_in_a_dict_scenario_is_an_input_error_naming_the_key():
    document = small_document()
    document["render"]["seeed"] = 3
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.render(document, base_dir=SMALL.parent)
    assert isinstance(error.value, ValueError)
    assert error.value.field == "render.seeed"
    assert error.value.file == str(SMALL.parent / "<scenario dict>")
    assert error.value.problem == "unknown key"
    assert str(error.value) == f"{SMALL.parent / '<scenario dict>'}: render.seeed: unknown key"
    # Without base_dir the paths start from the working directory, which errors name in full.
    document = small_document()
    document["render"]["frames"] = "three"
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.render(document)
    assert error.value.file == str(pathlib.Path.cwd() / "<scenario dict>")
    assert error.value.field == "render.frames"


def test_a_misspelt_required_key_in_a_dict_is_named_with_what_it_meant():
    document = small_document()
    trajectory = document["objects"][1]["trajectory"]
    trajectory["sped_mps"] = trajectory.pop("speed_mps")
    with pytest.raises(ladarsim.InputError) as error:
        ladarsim.render(document, base_dir=SMALL.parent)
    assert error.value.field == "objects[1].trajectory.sped_mps"
    assert error.value.problem == 'unknown key; did you mean "speed_mps"?'


def test_errors_in_files_and_arguments_name_what_is_wrong(tmp_path):
    with pytest.raises(ladarsim.InputError, match="nowhere.json"):
        ladarsim.render(tmp_path / "nowhere.json")
    with pytest.raises(ladarsim.InputError, match="frames: 0 is not a whole number from 1 to 10000000"):
        ladarsim.render(SMALL, frames=0)
    # Not pybind11's "incompatible function arguments" TypeError: the argument, in the user's terms.
    with pytest.raises(ladarsim.InputError, match="seed: -1 is not a whole number from 0"):
        ladarsim.render(SMALL, seed=-1)
    with pytest.raises(ladarsim.InputError, match="frames: expected a whole number from 1 to 10000000, found '3'"):
        ladarsim.render(SMALL, frames="3")
    with pytest.raises(ladarsim.InputError, match="threads: expected a whole number"):
        ladarsim.render(SMALL, threads=1.5)
    with pytest.raises(ladarsim.InputError, match="base_dir"):
        ladarsim.render(SMALL, base_dir=tmp_path)
    with pytest.raises(TypeError, match="a file's path or a dict"):
        ladarsim.render(42)
    with pytest.raises(TypeError, match=r"objects\[0\]\.name"):
        document = small_document()
        document["objects"][0]["name"] = {1, 2}
        ladarsim.render(document, base_dir=SMALL.parent)


def test_render_into_a_directory_writes_exactly_what_the_command_line_writes(cli_small, tmp_path):
    out = tmp_path / "small"
    summary = ladarsim.render(SMALL, out=out, threads=2)
    assert summary["frames"] == 3 and not summary["interrupted"]
    assert summary["out_dir"] == out
    assert summary["returns"] == sum(summary["returns_by_object"].values()) > 0

    def files(root):
        return sorted(str(p.relative_to(root)) for p in root.rglob("*") if p.is_file())

    assert files(out) == files(cli_small)
    same = [f for f in files(out) if f != "manifest.json"]
    match, mismatch, errors = filecmp.cmpfiles(out, cli_small, same, shallow=False)
    assert (mismatch, errors) == ([], [])
    assert "background.pcd" in match and "frames/000002.exr" in match
    ours, theirs = read_json(out / "manifest.json"), read_json(cli_small / "manifest.json")
    timing = {"frames", "totals"}
    assert {k: v for k, v in ours.items() if k not in timing} == {k: v for k, v in theirs.items() if k not in timing}
    untimed = [{k: v for k, v in f.items() if k != "render_s"} for f in ours["frames"]]
    assert untimed == [{k: v for k, v in f.items() if k != "render_s"} for f in theirs["frames"]]


def test_the_gil_is_released_while_a_frame_renders():
    # Heavy footprints make each frame take a while; while one renders, this thread must run.
    document = small_document()
    document["render"]["footprint_samples"] = 256
    stream = ladarsim.render(document, base_dir=SMALL.parent, threads=1)
    intervals, ticks, ticking, done = [], [], threading.Event(), threading.Event()

    def consume():
        ticking.wait()
        while True:
            start = time.perf_counter()
            try:
                next(stream)
            except StopIteration:
                break
            intervals.append((start, time.perf_counter()))
        done.set()

    worker = threading.Thread(target=consume)
    worker.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        ticking.set()
    worker.join()
    ticks = np.array(ticks)
    assert len(intervals) == 3
    # Holding the GIL through a frame would stop this thread for as long as the frame renders,
    # every frame; released, it only waits for the handing over of each frame's arrays.
    shortest = min(end - start for start, end in intervals)
    long_gaps = np.count_nonzero(np.diff(ticks) > 0.5 * shortest)
    assert long_gaps < len(intervals), f"{long_gaps} pauses longer than half a frame ({1e3 * shortest:.0f} ms)"
