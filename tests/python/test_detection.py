"""ladarsim.detect, ladarsim.evaluate and ladarsim.benchmark: the same reports as `ladarsim detect`,
`ladarsim eval --json` and `ladarsim benchmark --json`."""
import pytest

import ladarsim
from conftest import read_json, run_cli


@pytest.fixture(scope="module")
def cli_reports(cli_small, tmp_path_factory):
    out = tmp_path_factory.mktemp("detect")
    # The module does not classify tracks (the command line's default: its bundled classifier).
    run_cli("detect", cli_small, "--method", "vrbnn", "--lambda", 180, "--min-box", 0.3, "--classifier", "none",
            "--out", out / "detections.json")
    run_cli("eval", cli_small, "--detections", out / "detections.json", "--json", out / "scores.json")
    return read_json(out / "detections.json"), read_json(out / "scores.json"), out / "detections.json"


def test_detect_reports_what_the_command_line_reports(cli_small, cli_reports):
    detections, _, _ = cli_reports
    report = ladarsim.detect(ladarsim.Dataset(cli_small), method="vrbnn", lambda_=180, min_box_m=0.3)
    assert report == detections
    assert report["target"] == 2 and len(report["detections"]) == 3
    assert ladarsim.detect(str(cli_small), **{"lambda": 180, "min_box_m": 0.3}) == detections


def test_evaluate_scores_as_the_command_line_does(cli_small, cli_reports):
    detections, scores, detections_file = cli_reports
    assert ladarsim.evaluate(cli_small, detections) == scores
    assert ladarsim.evaluate(ladarsim.Dataset(cli_small), detections_file) == scores
    assert scores["frames"] == 3 and "mean_iou" in scores and "mean_iou_bev" in scores["point_box"]


def test_benchmark_scores_as_the_command_line_does(cli_small, tmp_path):
    run_cli("benchmark", cli_small, "--method", "vrbnn", "--lambda", 180, "--min-box", 0.3, "--json", tmp_path / "scores.json")
    scores = ladarsim.benchmark(cli_small, method="vrbnn", lambda_=180, min_box_m=0.3)
    assert scores == read_json(tmp_path / "scores.json")
    assert "eao" in scores["measures"] and 0 <= scores["eao"] <= 1 and "eao_bev" in scores["point_box"]


def test_unknown_or_mistyped_options_are_input_errors(cli_small):
    with pytest.raises(ladarsim.InputError, match=r"radius: unknown key"):
        ladarsim.detect(cli_small, radius=0.3)
    with pytest.raises(ladarsim.InputError, match=r"method"):
        ladarsim.detect(cli_small, method="dbscan")
    # A dict in place of a file is named by what it is, as Python names what is not a file.
    with pytest.raises(ladarsim.InputError, match=r"^<detections dict>: dataset: missing"):
        ladarsim.evaluate(cli_small, {"detections": []})
    report = ladarsim.detect(cli_small)
    with pytest.raises(ladarsim.InputError, match=r"detections: no detection for frame 0"):
        ladarsim.evaluate(cli_small, {"dataset": report["dataset"], "detections": []})
