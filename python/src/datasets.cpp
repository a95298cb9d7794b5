// ladarsim.Dataset: any dataset directory (rendered, or recorded by an importer), its frames read
// from their files only when asked for.
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "datasets.h"
#include "frames.h"
#include "json_objects.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/poses_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim::python {

namespace {

std::optional<double> number_in(const nlohmann::json& record, const char* key) {
    if (!record.is_object() || !record.contains(key) || !record[key].is_number()) return std::nullopt;
    return record[key].get<double>();
}

}  // namespace

Dataset::Dataset(const std::filesystem::path& dir)
    : dir_(dir), files_(frame_pcd_files(dir)), manifest_(read_json(dir / "manifest.json")) {
    if (!manifest_.is_object()) throw InputError((dir / "manifest.json").string(), "(file)", "must hold a JSON object");
    if (manifest_.contains("frames") && manifest_["frames"].is_array())
        for (const auto& record : manifest_["frames"])
            if (record.is_object() && record.contains("index") && record["index"].is_number_unsigned())
                records_[record["index"].get<std::uint64_t>()] = record;
}

std::uint64_t Dataset::index_of(std::size_t i) const {
    // frames/NNNNNN.pcd: the file names the frame (frame_file_stem).
    const std::string stem = files_[i].stem().string();
    std::uint64_t index = 0;
    const auto [end, error] = std::from_chars(stem.data(), stem.data() + stem.size(), index);
    return error == std::errc() && end == stem.data() + stem.size() ? index : i;
}

PythonFrame Dataset::frame(std::ptrdiff_t i) {
    const auto n = static_cast<std::ptrdiff_t>(files_.size());
    if (i < 0) i += n;
    if (i < 0 || i >= n) throw py::index_error("dataset index out of range");
    const std::filesystem::path& file = files_[static_cast<std::size_t>(i)];
    const std::filesystem::path exr = std::filesystem::path(file).replace_extension(".exr");
    std::vector<Return> returns;
    std::optional<RangeImage> image;
    {
        py::gil_scoped_release release;
        returns = read_frame_pcd(file);
        if (std::filesystem::exists(exr)) image = read_frame_exr(exr);
    }
    PythonFrame f;
    f.index = index_of(static_cast<std::size_t>(i));
    f.points = points_array(returns);
    if (image) {
        f.range_image = range_image_dict(*image);
        f.start_time_s = image->start_time_s;
        f.end_time_s = image->end_time_s;
    }
    if (const auto record = records_.find(f.index); record != records_.end()) {
        if (auto t = number_in(record->second, "start_time_s")) f.start_time_s = t;
        if (auto t = number_in(record->second, "end_time_s")) f.end_time_s = t;
        f.gimbal_az_rad = number_in(record->second, "gimbal_az_rad");
        f.gimbal_el_rad = number_in(record->second, "gimbal_el_rad");
    }
    if (const auto& poses = this->poses(); f.index < poses.size()) f.pose = pose_array(poses[f.index]);
    if (const auto* truth = ground_truth()) {
        const auto objects = truth->find(f.index);
        f.ground_truth = ground_truth_list(objects != truth->end() ? objects->second : std::vector<GroundTruthObject>{});
    }
    return f;
}

const std::map<std::uint64_t, std::vector<GroundTruthObject>>* Dataset::ground_truth() {
    if (!truth_loaded_) {
        const auto file = dir_ / "ground_truth.json";
        if (std::filesystem::exists(file)) {
            std::map<std::uint64_t, std::vector<GroundTruthObject>> truth;
            for (FrameGroundTruth& frame : read_ground_truth_json(file)) truth[frame.index] = std::move(frame.objects);
            truth_ = std::move(truth);
        }
        truth_loaded_ = true;
    }
    return truth_ ? &*truth_ : nullptr;
}

const std::vector<Eigen::Isometry3d>& Dataset::poses() {
    if (!poses_) {
        const auto file = dir_ / "poses.txt";
        poses_ = std::filesystem::exists(file) ? read_poses_txt(file) : std::vector<Eigen::Isometry3d>{};
    }
    return *poses_;
}

py::object Dataset::background() {
    if (!background_) {
        const auto file = dir_ / "background.pcd";
        if (!std::filesystem::exists(file)) return py::none();
        std::vector<Return> returns;
        {
            py::gil_scoped_release release;
            returns = read_frame_pcd(file);
        }
        background_ = points_array(returns);
    }
    return *background_;
}

void bind_datasets(py::module_& m) {
    py::class_<Dataset>(m, "Dataset", R"(A dataset directory: rendered (`ladarsim render`, ladarsim.render(out=...)) or recorded
(`ladarsim import-velodyne`, `import-ouster`). Frames are read from their files when indexed or
iterated: frames/NNNNNN.pcd as Frame.points, frames/NNNNNN.exr as Frame.range_image (None when
there is none), ground_truth.json as Frame.ground_truth (None when there is none).)")
        .def(py::init<std::filesystem::path>(), py::arg("dir"))
        .def("__len__", &Dataset::size)
        .def("__getitem__", &Dataset::frame, py::arg("index"))
        .def("__getitem__",
             [](Dataset& d, const py::slice& slice) {
                 py::size_t start = 0, stop = 0, step = 0, length = 0;
                 if (!slice.compute(d.size(), &start, &stop, &step, &length)) throw py::error_already_set();
                 py::list frames;
                 for (py::size_t k = 0; k < length; ++k) frames.append(d.frame(static_cast<std::ptrdiff_t>(start + k * step)));
                 return frames;
             })
        .def("__iter__", [](py::object self) { return DatasetIterator{self, 0}; })
        .def_property_readonly("path", &Dataset::dir)
        .def_property_readonly("manifest", [](const Dataset& d) { return to_python(d.manifest()); }, "manifest.json as a dict.")
        .def_property_readonly(
            "sensor", [](const Dataset& d) { return to_python(d.manifest().value("sensor", nlohmann::json())); },
            "The manifest's sensor document (with its 'derived' quantities) as a dict; None if it names none.")
        .def_property_readonly("background", &Dataset::background,
                               "background.pcd (the initial map) as a points array; None when the dataset has none.")
        .def("__repr__", [](const Dataset& d) {
            return "<ladarsim.Dataset " + d.dir().string() + ": " + std::to_string(d.size()) + " frames>";
        });

    py::class_<DatasetIterator>(m, "DatasetIterator")
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__", [](DatasetIterator& it) {
            Dataset& d = it.dataset.cast<Dataset&>();
            if (it.next >= d.size()) throw py::stop_iteration();
            return d.frame(static_cast<std::ptrdiff_t>(it.next++));
        });
}

}  // namespace ladarsim::python
