#pragma once
// A dataset in the KITTI object-detection layout, so that detectors trained on KITTI read it:
//   training/velodyne/NNNNNN.bin  float32 little-endian x y z intensity per return
//   training/label_2/NNNNNN.txt   one 15-field line per labelled object with returns in the frame
//   training/calib/NNNNNN.txt     P0..P3, R0_rect, Tr_velo_to_cam, Tr_imu_to_velo (kitti_calib_text)
//   ladarsim_export.json          where it came from, frame numbers, class map, intensity scale,
//                                 each label's exact ground-truth box
// No image_2: there is no camera. docs/kitti.md says what each field holds and why.
//
// Frames: ladarsim's sensor frame (x forward, y left, z up, the sensor at the origin) is KITTI's
// velodyne frame already, so points are written unrotated. The camera frame is the standard
// permutation of it (x right = -y, y down = -z, z forward = x), with R0_rect the identity.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/intensity_scale.h"
#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// A box as a KITTI label holds it: the tightest box turned about the vertical only that encloses
/// the oriented box (the same box when that one is turned about the vertical only), in the camera
/// frame of kitti_calib_text.
struct KittiBox {
    double height_m = 0.0;  ///< h, along the vertical (camera -y)
    double width_m = 0.0;   ///< w, across the object's heading
    double length_m = 0.0;  ///< l, along the object's heading (its model frame's x, the nose)
    Eigen::Vector3d bottom_centre_camera = Eigen::Vector3d::Zero();  ///< "location", m
    /// Heading about the camera's y axis: 0 when the nose points along camera +x (velodyne -y),
    /// -pi/2 along velodyne +x; in [-pi, pi).
    double rotation_y_rad = 0.0;
    /// Heading relative to the line of sight from the sensor: rotation_y - atan2(x, z) of the
    /// location, in [-pi, pi).
    double alpha_rad = 0.0;
};

/// The KITTI box of a ground-truth box in the sensor (velodyne) frame. Its heading is the box's
/// nose (own x axis) projected onto the horizontal plane (its left axis, turned back a quarter,
/// when the nose points straight up or down).
KittiBox kitti_box(const OrientedBox& box_sensor);

/// How far each face of a label box lies beyond the outermost return it holds, m: above the
/// float32 rounding of a return's coordinates at several kilometres (0.5 mm at 4 km) and the
/// labels' six decimals, so that readers counting points strictly inside a box (OpenPCDet's
/// points_in_boxes) count every one.
inline constexpr double kKittiLabelMargin_m = 0.01;

/// The label box of an object with `returns` (its returns in the sensor frame): kitti_box's,
/// grown about the same heading to the tightest box holding both ground truth's box and every
/// return kKittiLabelMargin_m inside its faces, as an annotator draws a box around what the
/// sensor saw. A return lies on its beam's axis, up to half a footprint beside the object whose
/// rim the footprint met, so ground truth's own box holds none of a small drone's returns.
/// Without returns it is kitti_box's.
KittiBox kitti_label_box(const OrientedBox& box_sensor, const std::vector<Eigen::Vector3d>& returns);

/// The label_2 type of a ladarsim class: the targets keep their own names ("drone" -> "Drone",
/// "bird" -> "Bird", "plane" -> "Plane"); the scene (building, terrain, tree, cloud, background)
/// is not labelled (std::nullopt), as KITTI leaves buildings and vegetation unlabelled.
std::optional<std::string> kitti_type(const std::string& object_class);

/// One label_2 line: type truncated occluded alpha bbox(4) h w l x y z rotation_y. With no
/// image, truncated is 0, occluded 3 (KITTI's "unknown") and the 2-D box -1 -1 -1 -1.
std::string kitti_label_line(const std::string& type, const KittiBox& box);

/// The calib file of every frame: P0..P3 = [I | 0], R0_rect = I, Tr_velo_to_cam the axis
/// permutation above, Tr_imu_to_velo = [I | 0] (no IMU: the sensor frame).
const std::string& kitti_calib_text();

/// The export's directory layout: marker ladarsim_export.json, own entries training/ (holding
/// only velodyne/, label_2/ and calib/ with NNNNNN files), ImageSets/ (train, val and test.txt)
/// and the marker.
const OutputLayout& kitti_layout();

struct KittiExportOptions {
    /// Label boxes are ground truth's exactly (kitti_box), not grown to hold the returns
    /// (kitti_label_box). ladarsim_export.json keeps the exact box of every label either way.
    bool exact_boxes = false;
};

struct KittiExportSummary {
    std::filesystem::path out;       ///< the export directory as written (see checked_output_dir)
    int frames = 0;
    std::uint64_t returns = 0;
    std::uint64_t labels = 0;
    float intensity_scale = 1.0f;    ///< KITTI intensity = ladarsim intensity / this
    std::vector<std::string> kept;   ///< the user's entries kept in `out` (see swap_in_output)
};

/// Writes dataset `dataset_dir` (frames/*.pcd, manifest.json, ground_truth.json when present)
/// into `out_dir` in the KITTI layout: the i-th frame in name order becomes NNNNNN = i. Intensity
/// is divided by the dataset's largest, so it spans KITTI's 0..1 and keeps its ratios across
/// frames. Staged and swapped in as a dataset is (checked_output_dir, swap_in_output). Throws
/// InputError naming the file and the problem for a missing directory, manifest or frames, a
/// malformed file, or ground truth without one of the frames.
KittiExportSummary export_kitti(const std::filesystem::path& dataset_dir, const std::filesystem::path& out_dir,
                                const KittiExportOptions& options = {}, const ExportProgress& progress = {});

/// One dataset of an export of several, and the split whose ImageSets file lists its frames.
struct KittiSource {
    std::filesystem::path dataset_dir;
    std::string split;  ///< "train", "val" or "test"
};

/// Several datasets (a campaign's sequences, `origin` the campaign) as one export: their frames
/// numbered on in the order given, with one intensity scale for all, all under training/ (each
/// labelled), and ImageSets/train.txt, val.txt and test.txt listing each split's frame numbers.
/// ladarsim_export.json names `origin`, each dataset (relative to it, with its id and split) and,
/// per frame, its dataset's place in that list; labels as `options` say. Throws as the
/// single-dataset export does.
KittiExportSummary export_kitti(const std::filesystem::path& origin, const std::vector<KittiSource>& sources,
                                const std::filesystem::path& out_dir, const KittiExportOptions& options = {},
                                const ExportProgress& progress = {});

}  // namespace ladarsim
