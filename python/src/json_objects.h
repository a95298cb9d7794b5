#pragma once
// JSON documents (scenarios, manifests, ground truth, reports) as the Python objects json.loads
// would make of them, and back.
#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace ladarsim::python {

namespace py = pybind11;

/// dict, list, str, int, float, bool or None.
py::object to_python(const nlohmann::json& value);

/// The reverse, for dict (str keys), list, tuple, str, os.PathLike (as its path), int, float,
/// bool, None, and NumPy scalars and arrays (by their tolist()). Throws TypeError naming the key
/// path below `where` (e.g. "objects[1].trajectory") of anything else.
nlohmann::json from_python(py::handle value, const std::string& where = "");

}  // namespace ladarsim::python
