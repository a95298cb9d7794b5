"""Full waveforms (render.waveforms: true, waveforms/NNNNNN.h5) read with h5py and with
ladarsim.read_waveforms: the returns of a frame are what a discriminator written here from
docs/waveforms.md finds in exactly these samples, each return's intensity is the sum of its
pulse's samples, and the files are the same bytes from run to run."""
import json

import h5py
import numpy as np
import pytest

import ladarsim
from conftest import SMALL, read_json, run_cli
from pcd_numpy import read_pcd

C = 299792458.0


def render(tmp_path, name, noise, waveforms=True, frames=2):
    scenario = json.loads(SMALL.read_text())
    for o in scenario["objects"]:
        o["model"] = str(SMALL.parent / o["model"])
    scenario["render"].update({"noise": noise, "frames": frames})
    # A dark building: at 160 m a bright one saturates the detector, whose clipped peak is a lower bound of the echo.
    scenario["objects"][0]["reflectance"] = 0.002
    if waveforms is not None:
        scenario["render"]["waveforms"] = waveforms
    (tmp_path / f"{name}.json").write_text(json.dumps(scenario))
    run_cli("render", tmp_path / f"{name}.json", "--out", tmp_path / name, "--quiet")
    return tmp_path / name


@pytest.fixture(scope="module")
def quiet(tmp_path_factory):
    return render(tmp_path_factory.mktemp("wf"), "quiet", noise=False)


@pytest.fixture(scope="module")
def noisy(tmp_path_factory):
    return render(tmp_path_factory.mktemp("wf"), "noisy", noise=True)


def read_h5(path):
    with h5py.File(path, "r") as f:
        d = {k: f[k][()] for k in ("column", "row", "time_s", "start_s", "first_sample", "sample_count", "samples")}
        d.update({k: f.attrs[k] for k in f.attrs if k != "units"})
    d["windows"] = [d["samples"][a:a + n].astype(np.float64) for a, n in zip(d["first_sample"], d["sample_count"])]
    return d


def discriminate(y, start_s, w):
    """Ranges and peaks of the pulses in one window, as docs/waveforms.md describes the discriminator."""
    dt, threshold, release, floor = w["sample_interval_s"], w["threshold_a"], w["release_a"], w["noise_floor_a"]
    found, searched_to, inside, in_valley, peak, valley = [], 0, False, False, 0, 0

    def measure(peak, searched_to):
        value, offset = y[peak], 0.0
        if 0 < peak < len(y) - 1 and y[peak - 1] > 0 and y[peak + 1] > 0 and y[peak] < w["saturation_a"]:
            a, b, c = np.log(y[peak - 1]), np.log(y[peak]), np.log(y[peak + 1])
            if a - 2 * b + c < 0:
                offset = np.clip(0.5 * (a - c) / (a - 2 * b + c), -0.5, 0.5)
                value = np.exp(b - 0.25 * (a - c) * offset)
        k = peak
        while k > searched_to and y[k - 1] >= 0.5 * value:
            k -= 1
        t = start_s + (k if k == searched_to else k - 1 + (0.5 * value - y[k - 1]) / (y[k] - y[k - 1])) * dt
        return 0.5 * C * (t + 0.5 * w["pulse_fwhm_s"]), value

    for k in range(len(y)):
        if (y[k] <= release) if inside else (y[k] <= threshold):
            if inside:
                found.append(measure(peak, searched_to))
                searched_to = k
            inside = in_valley = False
            continue
        if not inside:
            inside, in_valley, peak = True, False, k
        elif not in_valley:
            if y[k] > y[peak]:
                peak = k
            elif y[k] < 0.5 * y[peak]:
                in_valley, valley = True, k
        elif y[k] < y[valley]:
            valley = k
        elif y[k] > 2 * y[valley] and y[k] - y[valley] > 3 * floor:
            found.append(measure(peak, searched_to))
            searched_to, peak, in_valley = valley, k, False
    if inside:
        found.append(measure(peak, searched_to))
    return found


def beams_of(points):
    beams = {}
    for i, (c, r) in enumerate(zip(points["column"], points["row"])):
        beams.setdefault((int(c), int(r)), []).append(i)
    return beams


@pytest.mark.parametrize("which", ["quiet", "noisy"])
def test_the_returns_are_what_the_discriminator_finds_in_these_samples(which, request):
    dataset = request.getfixturevalue(which)
    checked = 0
    for k in range(2):
        points = read_pcd(dataset / "frames" / f"{k:06d}.pcd")
        w = read_h5(dataset / "waveforms" / f"{k:06d}.h5")
        assert w["frame"] == k
        ranges, times, spans = {}, {}, {}
        for c, r, t, start, y in zip(w["column"], w["row"], w["time_s"], w["start_s"], w["windows"]):
            beam = (int(c), int(r))
            ranges.setdefault(beam, []).extend(found for found, _ in discriminate(y, start, w))
            times.setdefault(beam, set()).add(float(t))
            spans.setdefault(beam, []).append((0.5 * C * start, 0.5 * C * (start + len(y) * w["sample_interval_s"])))
        beams = beams_of(points)
        for beam in set(beams) | set(ranges):
            indices = beams.get(beam, [])
            inside = [i for i in indices if any(a <= points["range_m"][i] <= b for a, b in spans.get(beam, []))]
            # A return outside every window is a false alarm, drawn for the whole range gate.
            assert all(points["source"][i] == 2 for i in indices if i not in inside)
            reported = sorted(float(points["range_m"][i]) for i in inside)
            found = sorted(ranges.get(beam, []))
            # None lost, none made up.
            assert len(found) == len(reported) and np.allclose(found, reported, rtol=0, atol=2e-4), (beam, found, reported)
            if reported:
                assert times[beam] == {float(points["time_s"][indices[0]])}
            checked += len(reported)
    assert checked > 100


def test_a_return_s_intensity_is_the_sum_of_its_pulse_s_samples(quiet, noisy):
    for dataset in (quiet, noisy):
        points = read_pcd(dataset / "frames" / "000000.pcd")
        w = read_h5(dataset / "waveforms" / "000000.h5")
        per_coulomb, dt = w["photoelectrons_per_coulomb"], w["sample_interval_s"]
        windows = {}
        for c, r, start, y in zip(w["column"], w["row"], w["start_s"], w["windows"]):
            windows.setdefault((int(c), int(r)), []).append((start, y))
        ratios = []
        for beam, indices in beams_of(points).items():
            real = [i for i in indices if points["source"][i] != 2]
            if len(real) != 1 or len(windows.get(beam, [])) != 1 or points["saturated"][real[0]]:
                continue  # one pulse alone in its window, not clipped: the window's sum is its energy
            (start, y), i = windows[beam][0], real[0]
            ratios.append(y.sum() * dt * per_coulomb / points["intensity"][i])
        assert len(ratios) > 100
        ratios = np.array(ratios)
        if dataset == quiet:
            assert np.abs(ratios - 1).max() <= 1e-3, (ratios.min(), ratios.max())
        else:
            # Within the noise: the peak the intensity is measured from carries the detector's noise (shot
            # noise of the echo itself, mostly), the sum averages it; unbiased, scattered by a few per mille.
            assert abs(np.median(ratios) - 1) <= 1e-3
            assert ratios.std() <= 0.01 and np.abs(ratios - 1).max() <= 0.03, (ratios.std(), ratios.min(), ratios.max())


def test_read_waveforms_gives_the_file_s_arrays(quiet):
    file = quiet / "waveforms" / "000001.h5"
    mine, theirs = ladarsim.read_waveforms(file), read_h5(file)
    for key in ("column", "row", "time_s", "start_s"):
        assert np.array_equal(mine[key], theirs[key])
    assert len(mine["samples"]) == len(theirs["windows"]) > 0
    assert all(np.array_equal(a, b) for a, b in zip(mine["samples"], theirs["windows"]))
    for key in ("sample_interval_s", "pulse_fwhm_s", "threshold_a", "release_a", "noise_floor_a", "photoelectrons_per_coulomb"):
        assert mine[key] == theirs[key]


def test_waveforms_are_the_same_bytes_each_run_and_absent_when_off(noisy, tmp_path):
    again = render(tmp_path, "again", noise=True)
    for k in range(2):
        name = f"{k:06d}.h5"
        assert (again / "waveforms" / name).read_bytes() == (noisy / "waveforms" / name).read_bytes()
    off = render(tmp_path, "off", noise=True, waveforms=None, frames=1)
    assert not (off / "waveforms").exists()
    assert "waveforms" not in read_json(off / "manifest.json")["render"]
