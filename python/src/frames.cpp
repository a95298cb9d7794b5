#include "frames.h"

#include <cstring>
#include <string>

#include <pybind11/stl.h>

#include "json_objects.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/dataset/ground_truth_file.h"

namespace ladarsim::python {

std::optional<double> PythonFrame::time_s() const {
    if (!start_time_s || !end_time_s) return std::nullopt;
    return 0.5 * (*start_time_s + *end_time_s);
}

namespace {

/// NumPy's type string of a PCD field: byte order, kind and size, a sub-array when COUNT > 1.
std::string numpy_format(const PcdField& field) {
    const char kind = field.type == 'F' ? 'f' : field.type == 'U' ? 'u' : 'i';
    std::string format = std::string("<") + kind + std::to_string(field.size);
    if (field.count != 1) format = "(" + std::to_string(field.count) + ",)" + format;
    return format;
}

template <typename T>
py::array_t<T> image_plane(const std::vector<T>& plane, const RangeImage& image) {
    const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(image.rows), static_cast<py::ssize_t>(image.columns)};
    py::array_t<T> array(shape);
    std::memcpy(array.mutable_data(), plane.data(), plane.size() * sizeof(T));
    return array;
}

}  // namespace

py::array points_array(const PcdCloud& cloud) {
    py::list names, formats, offsets;
    std::size_t offset = 0;
    for (const PcdField& field : cloud.fields()) {
        names.append(field.name);
        formats.append(numpy_format(field));
        offsets.append(offset);
        offset += static_cast<std::size_t>(field.size) * static_cast<std::size_t>(field.count);
    }
    py::dict spec;
    spec["names"] = names;
    spec["formats"] = formats;
    spec["offsets"] = offsets;
    spec["itemsize"] = cloud.point_step();
    const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(cloud.points())};
    py::array points(py::dtype::from_args(spec), shape);
    // The cloud's data is the PCD's binary DATA: little-endian, packed, point after point.
    if (!cloud.data().empty()) std::memcpy(points.mutable_data(), cloud.data().data(), cloud.data().size());
    return points;
}

py::array points_array(const std::vector<Return>& returns) { return points_array(frame_pcd_cloud(returns)); }

py::dict range_image_dict(const RangeImage& image) {
    py::dict channels;
    for (const RangeImageChannel& channel : range_image_channels(image)) {
        if (channel.float_plane) channels[channel.name] = image_plane(*channel.float_plane, image);
        else channels[channel.name] = image_plane(*channel.uint_plane, image);
    }
    return channels;
}

py::list ground_truth_list(const std::vector<GroundTruthObject>& objects) {
    py::list list;
    for (const GroundTruthObject& object : objects) list.append(to_python(ground_truth_object_json(object)));
    return list;
}

py::array pose_array(const Eigen::Isometry3d& world_from_sensor) {
    py::array_t<double> m({4, 4});
    auto out = m.mutable_unchecked<2>();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out(r, c) = world_from_sensor.matrix()(r, c);
    return m;
}

PythonFrame python_frame(const Frame& frame) {
    PythonFrame f;
    f.index = frame.index;
    f.start_time_s = frame.start_time_s;
    f.end_time_s = frame.end_time_s;
    f.points = points_array(frame.returns);
    f.range_image = range_image_dict(range_image_of(frame));
    f.ground_truth = ground_truth_list(frame.ground_truth);
    f.gimbal_az_rad = frame.gimbal_az_rad;
    f.gimbal_el_rad = frame.gimbal_el_rad;
    return f;
}

void bind_frames(py::module_& m) {
    py::class_<PythonFrame>(m, "Frame", R"(One frame: what the sensor reported for one scan, and where the objects really were.

points        NumPy structured array, one record per return, the fields and types of the
              frame's PCD file (x y z intensity range_m time_s beam_az beam_el column row
              return_index object_id snr source pulse_offset saturated; sensor frame, metres, radians)
range_image   dict of the EXR's channels (Y, range_m, intensity, object_id of the first return of
              every beam; strongest_range_m, strongest_intensity of its most intense), each a
              rows x columns array, row 0 the top line; None without an EXR
ground_truth  list of the frame's objects as ground_truth.json holds them; None without one
time_s        mid-scan time (the ground truth's poses are at it); start_time_s, end_time_s
pose          4 x 4 world-from-sensor matrix at the frame's start (poses.txt): pose @ [x, y, z, 1]
              takes a point to world coordinates; None for a dataset without poses.txt)")
        .def_readonly("index", &PythonFrame::index)
        .def_readonly("start_time_s", &PythonFrame::start_time_s)
        .def_readonly("end_time_s", &PythonFrame::end_time_s)
        .def_property_readonly("time_s", &PythonFrame::time_s)
        .def_readonly("points", &PythonFrame::points)
        .def_readonly("range_image", &PythonFrame::range_image)
        .def_readonly("ground_truth", &PythonFrame::ground_truth)
        .def_readonly("gimbal_az_rad", &PythonFrame::gimbal_az_rad)
        .def_readonly("gimbal_el_rad", &PythonFrame::gimbal_el_rad)
        .def_readonly("pose", &PythonFrame::pose)
        .def("__repr__", [](const PythonFrame& f) {
            return "<ladarsim.Frame " + std::to_string(f.index) + ": " + std::to_string(f.points.shape(0)) + " returns>";
        });
}

}  // namespace ladarsim::python
