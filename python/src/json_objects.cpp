#include "json_objects.h"

#include <cstdint>
#include <stdexcept>

namespace ladarsim::python {

py::object to_python(const nlohmann::json& value) {
    using Type = nlohmann::json::value_t;
    switch (value.type()) {
        case Type::null: return py::none();
        case Type::boolean: return py::bool_(value.get<bool>());
        case Type::number_integer: return py::int_(value.get<std::int64_t>());
        case Type::number_unsigned: return py::int_(value.get<std::uint64_t>());
        case Type::number_float: return py::float_(value.get<double>());
        case Type::string: return py::str(value.get_ref<const std::string&>());
        case Type::array: {
            py::list list;
            for (const auto& element : value) list.append(to_python(element));
            return list;
        }
        case Type::object: {
            py::dict dict;
            for (const auto& [key, element] : value.items()) dict[py::str(key)] = to_python(element);
            return dict;
        }
        default: throw std::logic_error("to_python: a JSON value with no Python counterpart");
    }
}

namespace {

std::string described(const std::string& where) { return where.empty() ? "the document" : where; }

}  // namespace

nlohmann::json from_python(py::handle value, const std::string& where) {
    if (value.is_none()) return nullptr;
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
    if (py::isinstance<py::int_>(value)) {
        // Within int64 as a signed JSON integer, beyond it up to uint64 as an unsigned one.
        int overflow = 0;
        const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
        if (overflow == 0) return static_cast<std::int64_t>(v);
        const unsigned long long u = PyLong_AsUnsignedLongLong(value.ptr());
        if (PyErr_Occurred()) {
            PyErr_Clear();
            throw py::type_error(described(where) + ": the integer " + py::repr(value).cast<std::string>() +
                                 " does not fit 64 bits");
        }
        return static_cast<std::uint64_t>(u);
    }
    if (py::isinstance<py::float_>(value)) return value.cast<double>();
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::isinstance<py::dict>(value)) {
        nlohmann::json object = nlohmann::json::object();
        for (const auto& [key, element] : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(key))
                throw py::type_error(described(where) + ": the key " + py::repr(key).cast<std::string>() + " is not a str");
            const std::string name = key.cast<std::string>();
            object[name] = from_python(element, where.empty() ? name : where + "." + name);
        }
        return object;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        nlohmann::json array = nlohmann::json::array();
        std::size_t i = 0;
        for (const auto& element : value) array.push_back(from_python(element, where + "[" + std::to_string(i++) + "]"));
        return array;
    }
    if (py::hasattr(value, "__fspath__")) return py::module_::import("os").attr("fspath")(value).cast<std::string>();
    if (py::hasattr(value, "tolist")) return from_python(value.attr("tolist")(), where);  // NumPy scalars and arrays
    throw py::type_error(described(where) + ": a " + py::str(py::type::of(value).attr("__name__")).cast<std::string>() +
                         " has no JSON counterpart (use dict, list, str, int, float, bool or None)");
}

}  // namespace ladarsim::python
