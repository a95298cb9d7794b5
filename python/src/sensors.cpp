// ladarsim.Sensor: a bundled or file-defined sensor, its document and its derived quantities.
#include <filesystem>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "json_objects.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/core/units.h"

namespace ladarsim::python {

void bind_sensors(py::module_& m) {
    using sensor_model::Sensor;
    py::class_<Sensor>(m, "Sensor", R"(A sensor as its parts (docs/sensor.md): scan pattern, transmitter, optics,
receiver, gimbal. `document` is the sensor document with its derived quantities, as a dataset's
manifest records it under "sensor".)")
        .def_static("preset", &sensor_model::sensor_preset, py::arg("name"),
                    "A bundled sensor (assets/sensors/): paper_ladar, velodyne_vlp16, ouster_os-1-32-g, ...")
        .def_static("presets", &sensor_model::sensor_presets, "The names of the bundled sensors.")
        .def_static(
            "from_file",
            [](const std::filesystem::path& file) {
                const nlohmann::json document = read_json(file);
                return sensor_model::read_sensor(document, file.string());
            },
            py::arg("path"), "A sensor file (as `ladarsim sensor from-ouster` writes, or assets/sensors/*.json).")
        .def_static(
            "from_document",
            [](const py::dict& document) { return sensor_model::read_sensor(from_python(document), "<sensor dict>"); },
            py::arg("document"),
            "A sensor document held as a dict, e.g. a dataset's manifest['sensor'] (its 'derived' is recomputed).")
        .def_readonly("name", &Sensor::name)
        .def_readonly("description", &Sensor::description)
        .def_property_readonly("document", [](const Sensor& s) { return to_python(sensor_model::to_json(s)); })
        .def_property_readonly("derived", [](const Sensor& s) { return to_python(sensor_model::to_json(s)["derived"]); })
        .def_property_readonly("pattern", [](const Sensor& s) { return s.scan->pattern(); })
        .def_property_readonly("columns", [](const Sensor& s) { return s.scan->columns(); }, "Beams in azimuth.")
        .def_property_readonly("rows", [](const Sensor& s) { return s.scan->rows(); }, "Beams in elevation.")
        .def_property_readonly("field_az_deg", [](const Sensor& s) { return s.scan->field_az_deg(); })
        .def_property_readonly("field_el_deg", [](const Sensor& s) { return s.scan->field_el_deg(); })
        .def_property_readonly("pitch_az_mrad", [](const Sensor& s) { return s.scan->pitch_az_rad() / kMrad; })
        .def_property_readonly("pitch_el_mrad", [](const Sensor& s) { return s.scan->pitch_el_rad() / kMrad; })
        .def_property_readonly("frame_rate_hz", [](const Sensor& s) { return s.scan->frame_rate_hz(); })
        .def_property_readonly("beams_per_second", &Sensor::beams_per_second)
        .def_property_readonly("pulses_per_beam", &Sensor::pulses_per_beam)
        .def_property_readonly("range_gate_s", &Sensor::range_gate_s)
        .def("__repr__", [](const Sensor& s) {
            return "<ladarsim.Sensor " + s.name + ": " + std::to_string(s.scan->columns()) + " x " +
                   std::to_string(s.scan->rows()) + " beams>";
        });
}

}  // namespace ladarsim::python
