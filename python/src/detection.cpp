// ladarsim.detect, ladarsim.evaluate and ladarsim.benchmark: Algorithm 1 over a dataset and its
// scores, the reports `ladarsim detect`, `ladarsim eval --json` and `ladarsim benchmark --json` write.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "datasets.h"
#include "json_objects.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/detect/scoring.h"
#include "ladarsim/detect/sequence.h"

namespace ladarsim::python {

namespace {

/// A Dataset's directory, or a directory given as a path.
std::filesystem::path dataset_dir(const py::handle& dataset) {
    if (py::isinstance<Dataset>(dataset)) return dataset.cast<const Dataset&>().dir();
    if (!py::isinstance<py::str>(dataset) && !py::hasattr(dataset, "__fspath__"))
        throw py::type_error("dataset must be a ladarsim.Dataset or a directory's path, not " +
                             py::str(py::type::of(dataset).attr("__name__")).cast<std::string>());
    return dataset.cast<std::filesystem::path>();
}

detect::Sequence sequence_of(const py::handle& dataset) {
    const std::filesystem::path dir = dataset_dir(dataset);
    py::gil_scoped_release release;
    return detect::load_sequence(dir);
}

/// A named detector over a dataset: `run` (detection_report or benchmark_report) of the detector
/// `method` and `options` (read_detector_config's keys, `lambda_` for `lambda`, and `target`) describe.
using DetectorRun = std::function<nlohmann::json(const detect::Sequence&, const detect::DetectorConfig&, std::optional<std::uint32_t>)>;
py::object run_detector(const char* caller, const py::handle& dataset, const std::string& method, const py::kwargs& options,
                        const DetectorRun& run) {
    nlohmann::json config = {{"method", method}};
    std::optional<std::uint32_t> target;
    for (const auto& [key, value] : options) {
        std::string name = key.cast<std::string>();
        if (name == "target") {
            if (!value.is_none()) target = value.cast<std::uint32_t>();
            continue;
        }
        if (name == "lambda_") name = "lambda";  // `lambda` is a Python keyword
        config[name] = from_python(value, name);
    }
    const detect::DetectorConfig detector = detect::read_detector_config(config, caller);
    const detect::Sequence sequence = sequence_of(dataset);
    if (sequence.background.empty())
        PyErr_WarnEx(PyExc_UserWarning, (dataset_dir(dataset).string() + ": no background.pcd: nothing is subtracted").c_str(), 1);
    nlohmann::json report;
    {
        py::gil_scoped_release release;
        report = run(sequence, detector, target);
    }
    return to_python(report);
}

py::object detect_dataset(const py::handle& dataset, const std::string& method, const py::kwargs& options) {
    return run_detector("ladarsim.detect()", dataset, method, options,
                        [](const auto& s, const auto& c, auto target) { return detect::detection_report(s, c, target); });
}

py::object benchmark_dataset(const py::handle& dataset, const std::string& method, const py::kwargs& options) {
    return run_detector("ladarsim.benchmark()", dataset, method, options,
                        [](const auto& s, const auto& c, auto target) { return detect::benchmark_report(s, c, target); });
}

py::object evaluate_detections(const py::handle& dataset, const py::handle& detections) {
    nlohmann::json report;
    std::string file = "<detections dict>";
    if (py::isinstance<py::dict>(detections)) {
        report = from_python(detections);
    } else {
        const auto path = detections.cast<std::filesystem::path>();
        file = path.string();
        report = read_json(path);
    }
    const detect::Sequence sequence = sequence_of(dataset);
    nlohmann::json scores;
    {
        py::gil_scoped_release release;
        scores = detect::evaluate_report(sequence, report, file);
    }
    return to_python(scores);
}

}  // namespace

void bind_detection(py::module_& m) {
    m.def("detect", &detect_dataset, py::arg("dataset"), py::arg("method") = "vrbnn",
          R"(Run Algorithm 1 (docs/detection.md) over a dataset (a Dataset or its directory) and return
the report `ladarsim detect` writes: {"method", "config", "dataset", "detections", "tracks", and
with ground truth "target"}. method: "rbnn", "vrbnn" or "kalman"; options: radius_m, lambda (or
lambda_), bias_m, resolution_m, range_tolerance_m, min_neighbours, max_diagonal_m, max_speed_mps,
min_box_m, max_object_diagonal_m, range_coherence_m, coherent_fraction (clutter rejection),
target_size_m (the sensor-aware box's size prior, [x, y, z]), and target (the ground-truth id to
score; default the first drone). Unknown options raise InputError.)");
    m.def("evaluate", &evaluate_detections, py::arg("dataset"), py::arg("detections"),
          R"(Score the boxes of a detection report (the dict detect() returns, any detector's in its format,
or the path of such a file) against the dataset's ground truth, and nothing else: the dict
`ladarsim eval --json` writes (measures; mean_l2_m; mean_iou, mean_iou_bev of the sensor-aware box
and the same of the box around the points under point_box; frames_lost, success, precision,
per_frame; with tracks mota, motp_m, id_switches, ap_centre, ap_centre_3d, tracking). Entries are
matched to frames by "frame". EAO needs the tracker in the loop: benchmark().)");
    m.def("benchmark", &benchmark_dataset, py::arg("dataset"), py::arg("method") = "vrbnn",
          R"(Run a detector as detect() does (same method and options) and score it as it runs: the dict
`ladarsim benchmark --json` writes, evaluate()'s plus VOT's supervised EAO (eao, eao_bev,
eao_interval, failures, the same under point_box; per frame supervised_iou, initialised).)");
}

}  // namespace ladarsim::python
