#pragma once
// A frame as Python sees it, rendered or read back from a dataset: its returns as a NumPy
// structured array with the PCD's fields, its range image as the EXR's channels, its ground truth
// as ground_truth.json holds it.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "ladarsim/dataset/exr_file.h"
#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/pcd_file.h"

namespace ladarsim::python {

namespace py = pybind11;

struct PythonFrame {
    std::uint64_t index = 0;
    std::optional<double> start_time_s;  ///< absent for a dataset whose manifest does not record it
    std::optional<double> end_time_s;
    py::array points;
    py::object range_image = py::none();   ///< dict of channel name -> (rows, columns) array, or None
    py::object ground_truth = py::none();  ///< list of object dicts, or None without ground truth
    std::optional<double> gimbal_az_rad;
    std::optional<double> gimbal_el_rad;
    py::object pose = py::none();  ///< 4 x 4 world-from-sensor at the frame's start, or None

    /// Mid-scan time, at which the ground truth's poses are evaluated.
    std::optional<double> time_s() const;
};

/// The cloud's points as a structured array: one record per point, the cloud's fields in its
/// order with their PCD TYPE and SIZE (F4 -> <f4, U2 -> <u2, ...), packed as in the file.
py::array points_array(const PcdCloud& cloud);

/// The returns as write_frame_pcd writes them (frame_pcd_cloud), as points_array.
py::array points_array(const std::vector<Return>& returns);

/// The EXR's channels (range_image_channels: Y, range_m, intensity, object_id, and the strongest
/// return's range and intensity), each a rows x columns array, row 0 the top raster line.
py::dict range_image_dict(const RangeImage& image);

/// The objects of a frame as ground_truth.json holds them.
py::list ground_truth_list(const std::vector<GroundTruthObject>& objects);

/// A pose as a 4 x 4 homogeneous matrix.
py::array pose_array(const Eigen::Isometry3d& world_from_sensor);

/// A frame just rendered: everything a dataset would hold of it.
PythonFrame python_frame(const Frame& frame);


}  // namespace ladarsim::python
