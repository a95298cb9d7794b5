// The `ladarsim` Python module: render scenarios frame by frame into NumPy arrays or into
// datasets, read any dataset, run and score detection, as the command line does.
#include <string>

#include "bindings.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/log_lines.h"

namespace ladarsim::python {

void bind_errors(py::module_& m) {
    // Kept for the life of the process: the translator may run until the interpreter exits.
    static PyObject* const input_error =
        py::exception<InputError>(m, "InputError", PyExc_ValueError).inc_ref().ptr();
    py::setattr(input_error, "__doc__", py::str(R"(Bad input: a file (or the dict given in its place: "<scenario dict>" after its base_dir,
"<sensor dict>", "<detections dict>"), the field in it and the problem, in
the one-line message the command line prints; also as the attributes file, field and problem.)"));
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const InputError& e) {
            py::object error = py::reinterpret_borrow<py::object>(input_error)(e.what());
            error.attr("file") = e.file();
            error.attr("field") = e.field();
            error.attr("problem") = e.problem();
            PyErr_SetObject(input_error, error.ptr());
        }
    });
}

}  // namespace ladarsim::python

PYBIND11_MODULE(ladarsim, m) {
    using namespace ladarsim::python;
    m.doc() = R"(ladarsim: a physically based LADAR simulator (README.md, docs/).

render(scenario, ...)      frames one at a time, or a dataset directory with out=DIR
Dataset(dir)               a rendered or recorded dataset, read lazily
Campaign(dir, split=None)  a campaign's sequences (`ladarsim campaign`), each with its Dataset
detect(dataset, ...)       Algorithm 1 over a dataset, as `ladarsim detect` reports it
evaluate(dataset, report)  the scores of its boxes, as `ladarsim eval --json` writes them
benchmark(dataset, ...)    a detector run and scored with EAO, as `ladarsim benchmark --json`
Sensor.preset(name)        a sensor, its document and derived quantities
read_waveforms(file)       a frame's full waveforms (render.waveforms) as NumPy arrays
InputError                 bad input (a ValueError), naming the file, field and problem)";
    m.attr("__version__") = ladarsim::software_json().at("version").get<std::string>();
    // Warnings and notes as the command line words them (spdlog's own format dates each line).
    ladarsim::use_ladarsim_log_lines();
    bind_errors(m);
    bind_frames(m);
    bind_sensors(m);
    bind_render(m);
    bind_datasets(m);
    bind_campaigns(m);
    bind_detection(m);
    bind_waveforms(m);
}
