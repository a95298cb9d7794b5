#pragma once
// The parts of the `ladarsim` Python module, one file each, added to it by module.cpp.
#include <pybind11/pybind11.h>

namespace ladarsim::python {

namespace py = pybind11;

void bind_errors(py::module_& m);
void bind_frames(py::module_& m);
void bind_sensors(py::module_& m);
void bind_render(py::module_& m);
void bind_datasets(py::module_& m);
void bind_campaigns(py::module_& m);
void bind_detection(py::module_& m);
void bind_waveforms(py::module_& m);

}  // namespace ladarsim::python
