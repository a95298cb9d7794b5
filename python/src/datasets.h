#pragma once
// A dataset directory read lazily from Python.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "frames.h"
#include "ladarsim/dataset/ground_truth_file.h"

namespace ladarsim::python {

namespace py = pybind11;

class Dataset {
public:
    /// Lists the frames and reads manifest.json; throws InputError for a directory without them.
    explicit Dataset(const std::filesystem::path& dir);

    std::size_t size() const { return files_.size(); }
    /// Frame i of the frames in name order (negative: from the end); its files are read now.
    PythonFrame frame(std::ptrdiff_t i);
    const std::filesystem::path& dir() const { return dir_; }
    const nlohmann::json& manifest() const { return manifest_; }
    /// The initial map, read on first use; None without background.pcd.
    py::object background();

private:
    std::uint64_t index_of(std::size_t i) const;
    /// ground_truth.json by frame index, read on first use; null without one.
    const std::map<std::uint64_t, std::vector<GroundTruthObject>>* ground_truth();
    /// poses.txt, a line per frame index, read on first use; empty without one.
    const std::vector<Eigen::Isometry3d>& poses();

    std::filesystem::path dir_;
    std::vector<std::filesystem::path> files_;
    nlohmann::json manifest_;
    std::map<std::uint64_t, nlohmann::json> records_;  ///< the manifest's frame records by index
    bool truth_loaded_ = false;
    std::optional<std::map<std::uint64_t, std::vector<GroundTruthObject>>> truth_;
    std::optional<py::array> background_;
    std::optional<std::vector<Eigen::Isometry3d>> poses_;
};

struct DatasetIterator {
    py::object dataset;
    std::size_t next = 0;
};

}  // namespace ladarsim::python
