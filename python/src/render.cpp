// ladarsim.render: a scenario (file or dict) rendered frame by frame into NumPy arrays, or into a
// dataset directory exactly as `ladarsim render` writes it.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "bindings.h"
#include "frames.h"
#include "json_objects.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::python {

namespace {

using sensor_model::Scenario;

constexpr const char* kCaller = "ladarsim.render()";

/// A scenario file (str or path), or a scenario document held as a dict whose relative paths
/// start from `base_dir` (default: the working directory, named in full so that an error says
/// where the paths it names start from).
Scenario scenario_of(const py::handle& scenario, const py::object& base_dir) {
    if (py::isinstance<py::dict>(scenario)) {
        const nlohmann::json document = from_python(scenario);
        const std::filesystem::path base =
            base_dir.is_none() ? std::filesystem::current_path() : base_dir.cast<std::filesystem::path>();
        py::gil_scoped_release release;
        return sensor_model::load_scenario(document, base);
    }
    if (!base_dir.is_none())
        throw InputError(kCaller, "base_dir", "applies to a scenario given as a dict; a file's paths start from its own folder");
    if (!py::isinstance<py::str>(scenario) && !py::hasattr(scenario, "__fspath__"))
        throw py::type_error("ladarsim.render: scenario must be a file's path or a dict, not " +
                             py::str(py::type::of(scenario).attr("__name__")).cast<std::string>());
    const auto file = scenario.cast<std::filesystem::path>();
    py::gil_scoped_release release;
    return sensor_model::load_scenario(file);
}

/// The frames of one scenario, rendered one per next(): what the iteration holds is the scene
/// and the renderer, never more than the frame being handed over.
class FrameStream {
public:
    FrameStream(Scenario scenario, int threads)
        : scenario_(std::make_unique<Scenario>(std::move(scenario))),
          threads_(threads > 0 ? threads : tbb::info::default_concurrency()) {
        py::gil_scoped_release release;  // builds the scene's ray-tracing structures
        renderer_ = std::make_unique<sensor_model::FrameRenderer>(*scenario_);
    }

    PythonFrame next() {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C between frames
        if (busy_) throw py::value_error("ladarsim.render: the frames are already being rendered in another thread");
        if (next_ >= scenario_->render.frames) throw py::stop_iteration();
        busy_ = true;
        Frame frame;
        try {
            py::gil_scoped_release release;
            tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads_));
            frame = renderer_->render(static_cast<std::uint64_t>(next_));
        } catch (...) {
            busy_ = false;
            throw;
        }
        busy_ = false;
        ++next_;
        PythonFrame f = python_frame(frame);
        f.pose = pose_array(scenario_->mount.world_from_sensor());
        return f;
    }

    int frames() const { return scenario_->render.frames; }
    int remaining() const { return scenario_->render.frames - next_; }
    const Scenario& scenario() const { return *scenario_; }

private:
    std::unique_ptr<Scenario> scenario_;  // the renderer refers to it
    std::unique_ptr<sensor_model::FrameRenderer> renderer_;
    int threads_;
    int next_ = 0;
    bool busy_ = false;
};

py::dict summary_dict(const sensor_model::DatasetSummary& s) {
    py::dict by_object;
    for (const auto& [id, count] : s.returns_by_object) by_object[py::int_(id)] = count;
    py::dict d;
    d["out_dir"] = s.out_dir;
    d["frames"] = s.frames;
    d["returns"] = s.returns;
    d["returns_by_object"] = by_object;
    d["render_seconds"] = s.render_seconds;
    d["beams_per_second"] = s.beams_per_second;
    d["background_points"] = s.background_points;
    d["interrupted"] = s.interrupted;
    return d;
}

/// render_dataset, stopped cleanly (finished frames kept in OUT.partial) by Ctrl-C.
py::dict render_to_directory(Scenario scenario, const std::filesystem::path& out, std::optional<int> frames,
                             std::optional<std::uint64_t> seed, int threads, bool resume) {
    sensor_model::DatasetOptions options;
    options.out_dir = out;
    options.frames = frames;
    options.seed = seed;
    options.threads = threads;
    options.resume = resume;
    std::atomic<bool> stop{false};
    options.stop = &stop;
    std::optional<py::error_already_set> interrupt;
    options.progress = [&](int, int) {
        py::gil_scoped_acquire gil;
        if (!interrupt && PyErr_CheckSignals() != 0) {
            interrupt.emplace();  // takes the pending KeyboardInterrupt, raised once the run has stopped
            stop.store(true);
        }
    };
    sensor_model::DatasetSummary summary;
    {
        py::gil_scoped_release release;
        summary = sensor_model::render_dataset(std::move(scenario), options);
    }
    if (interrupt) {
        // In place of the KeyboardInterrupt taken (and so cleared) above: one saying what to do next.
        PyErr_SetString(PyExc_KeyboardInterrupt,
                        ("stopped after " + std::to_string(summary.frames) + " frames; the finished frames are in " +
                         summary.out_dir.string() + ".partial: render(..., out=DIR, resume=True) continues")
                            .c_str());
        throw py::error_already_set();
    }
    return summary_dict(summary);
}

/// An optional whole-number argument from `lo` to `hi`, or an InputError naming it: pybind11's own
/// conversion of seed=-1 or frames="3" says only "incompatible function arguments".
std::optional<std::uint64_t> whole_number(const py::object& value, const char* name, std::uint64_t lo, std::uint64_t hi) {
    if (value.is_none()) return std::nullopt;
    const std::string range = "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
    if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
        throw InputError(kCaller, name, "expected " + range + ", found " + std::string(py::repr(value)));
    if (value < py::int_(lo) || value > py::int_(hi))
        throw InputError(kCaller, name, std::string(py::repr(value)) + " is not " + range);
    return value.cast<std::uint64_t>();
}

py::object render(const py::handle& scenario, const py::object& frames_arg, const py::object& seed_arg,
                  const py::object& threads_arg, const py::object& base_dir, std::optional<std::filesystem::path> out, bool resume) {
    const auto whole_frames = whole_number(frames_arg, "frames", 1, sensor_model::kMaxFrames);
    const std::optional<int> frames = whole_frames ? std::optional<int>(static_cast<int>(*whole_frames)) : std::nullopt;
    const std::optional<std::uint64_t> seed = whole_number(seed_arg, "seed", 0, std::numeric_limits<std::uint64_t>::max());
    const auto whole_threads = whole_number(threads_arg, "threads", 0, std::numeric_limits<int>::max());
    const int threads = static_cast<int>(whole_threads.value_or(0));  // 0: every core
    if (resume && !out) throw InputError(kCaller, "resume", "continues a render into a directory: give out=DIR");
    Scenario s = scenario_of(scenario, base_dir);
    if (out) return render_to_directory(std::move(s), *out, frames, seed, threads, resume);
    // As render_dataset applies them, before the renderer is built.
    if (frames) s.render.frames = *frames;
    if (seed) s.render.seed = *seed;
    return py::cast(FrameStream(std::move(s), threads));
}

}  // namespace

void bind_render(py::module_& m) {
    py::class_<FrameStream>(m, "FrameStream", "The frames of ladarsim.render(), rendered one at a time as they are iterated.")
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__", &FrameStream::next)
        .def("__len__", &FrameStream::remaining)
        .def_property_readonly("frames", &FrameStream::frames, "Frames in the run.")
        .def_property_readonly("scenario", [](const FrameStream& f) { return to_python(f.scenario().source); },
                               "The scenario document as read (its extends applied).")
        .def_property_readonly("sensor", [](const FrameStream& f) { return f.scenario().sensor; });

    m.def("render", &render, py::arg("scenario"), py::arg("frames") = py::none(),
          py::arg("seed") = py::none(), py::arg("threads") = py::none(), py::arg("base_dir") = py::none(),
          py::arg("out") = py::none(), py::arg("resume") = false,
          R"(Render a scenario (docs/scenario.md): a file's path, or a dict in the scenario format whose
`extends` and relative paths start from base_dir (default: the working directory; errors name
"BASE_DIR/<scenario dict>", the working directory in full when base_dir is not given).

Without out: an iterator of Frame, each rendered when it is asked for (one frame in memory at a
time), equal value for value to the frames `ladarsim render` writes for the same scenario and seed.
With out=DIR: writes the dataset exactly as `ladarsim render --out DIR` does and returns a summary
dict; resume=True continues a run interrupted by Ctrl-C (its finished frames are in DIR.partial).

frames, seed override the scenario's render.frames and render.seed; threads (default all cores)
does not change the output. Ctrl-C (KeyboardInterrupt) stops after the current frame.)");
}

}  // namespace ladarsim::python
