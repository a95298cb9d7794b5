#include "ladarsim/scene/background_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <pcl/common/centroid.h>
#include <pcl/common/eigen.h>
#include <flann/flann.hpp>
#include <pcl/point_types.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/pcd_file.h"
#include "ladarsim/scene/las_file.h"
#include "ladarsim/scene/ply_file.h"

namespace ladarsim::scene {

namespace {

/// Least-squares plane of a neighbourhood: its normal, unless the points do not span a plane
/// (fewer than three distinct points, or all on one line), and the direction the points spread
/// along most. PCL's NormalEstimation returns NaN only for the first case and an arbitrary normal
/// for the second, so the eigenvalues are checked here.
struct NeighbourhoodPlane {
    std::optional<Eigen::Vector3f> normal;
    Eigen::Vector3f axis = Eigen::Vector3f::Zero();  ///< largest spread; zero without three points
};

NeighbourhoodPlane fit_plane(const pcl::PointCloud<pcl::PointXYZ>& cloud, const pcl::Indices& neighbours) {
    NeighbourhoodPlane plane;
    Eigen::Matrix3d covariance;
    Eigen::Vector4d centroid;
    if (pcl::computeMeanAndCovarianceMatrix(cloud, neighbours, covariance, centroid) < 3) return plane;
    Eigen::Matrix3d eigenvectors;
    Eigen::Vector3d eigenvalues;  // ascending
    pcl::eigen33(covariance, eigenvectors, eigenvalues);
    if (eigenvectors.col(2).allFinite()) plane.axis = eigenvectors.col(2).cast<float>().normalized();
    // A middle eigenvalue a millionth of the largest means the points lie on a line to within
    // a thousandth of its length: any normal about that line fits equally well.
    if (!(eigenvalues[1] > 1e-6 * eigenvalues[2])) return plane;
    const Eigen::Vector3f normal = eigenvectors.col(0).cast<float>().normalized();
    if (normal.allFinite()) plane.normal = normal;
    return plane;
}

/// The unit vector closest to `towards` that is perpendicular to `axis` (a line's best normal as
/// seen from there); `towards` itself when the axis is unknown or along it.
Eigen::Vector3f facing_across(const Eigen::Vector3f& towards, const Eigen::Vector3f& axis) {
    const Eigen::Vector3f across = towards - towards.dot(axis) * axis;
    return across.norm() > 1e-6f ? across.normalized() : towards;
}

// A ground-based scanner samples a surface along scan lines: the neighbours of a point lie on
// the cone its channel swept, spread along the line and, by range noise, along the lines of sight.
// Their plane fit then contains the lines of sight: a plane within this cosine of edge-on to the
// scanner that recorded it is an artefact of the sampling (such a surface would hardly return).
constexpr float kScanLineCos = 0.1f;

// Each point's disc: its normal from the plane of its nearest neighbours, facing where the map was
// recorded from, and its radius from the nearest four.
void estimate_discs(const pcl::PointCloud<pcl::PointXYZ>& cloud, int normal_neighbours, const std::optional<Eigen::Vector3d>& scanner,
                    BackgroundMap& map, BackgroundLoadReport& rep) {
    const std::size_t n = cloud.size();
    // FLANN's k-d tree as PCL's KdTreeFLANN builds and searches it (the same neighbours), queried
    // a block of points at a time: PCL's one query a call opens an OpenMP region each time, which
    // cost as much as the search, and blocks spread over the caller's threads.
    static_assert(sizeof(pcl::PointXYZ) == 4 * sizeof(float), "PointXYZ is x y z and a pad");
    // FLANN's matrices take float* but only read the points.
    float* xyz = const_cast<float*>(&cloud[0].x);
    flann::Index<flann::L2_Simple<float>> tree(flann::Matrix<float>(xyz, n, 3, sizeof(pcl::PointXYZ)),
                                               flann::KDTreeSingleIndexParams(15));
    tree.buildIndex();

    // The search returns the point itself first, then its neighbours by distance.
    const int k_normal = std::clamp(normal_neighbours, 3, static_cast<int>(n));
    const int k_search = std::max(k_normal, 5);
    const auto k = static_cast<std::size_t>(k_search);
    map.normals.resize(n);
    map.radii_m.resize(n);
    enum class NormalFrom : std::uint8_t { plane, degenerate, scan_line };
    std::vector<NormalFrom> normal_from(n, NormalFrom::plane);
    constexpr std::size_t kBlock = 4096;
    tbb::parallel_for(std::size_t{0}, (n + kBlock - 1) / kBlock, [&](std::size_t block) {
        const std::size_t first = block * kBlock, count = std::min(kBlock, n - first);
        std::vector<int> found(count * k);
        std::vector<float> squared(count * k);
        flann::Matrix<int> indices(found.data(), count, k);
        flann::Matrix<float> squared_distances(squared.data(), count, k);
        flann::SearchParams search(-1, 0.0f, true);
        search.cores = 1;
        tree.knnSearch(flann::Matrix<float>(xyz + 4 * first, count, 3, sizeof(pcl::PointXYZ)), indices, squared_distances,
                       k, search);
        for (std::size_t j = 0; j < count; ++j) {
            const std::size_t i = first + j;
            const int* neighbours = indices[j];
            const float* d2 = squared_distances[j];
            const pcl::Indices plane_points(neighbours, neighbours + k_normal);
            const NeighbourhoodPlane plane = fit_plane(cloud, plane_points);
            // Discs face where the map was recorded from: up for an airborne survey, else its scanner.
            const Eigen::Vector3f towards =
                scanner ? Eigen::Vector3f((*scanner - map.points_world[i]).normalized().cast<float>())
                    : Eigen::Vector3f::UnitZ();
            if (!plane.normal) {
                map.normals[i] = scanner ? facing_across(towards, plane.axis) : towards;
                normal_from[i] = NormalFrom::degenerate;
            } else if (scanner && std::abs(plane.normal->dot(towards)) < kScanLineCos) {
                map.normals[i] = towards;
                normal_from[i] = NormalFrom::scan_line;
            } else {
                map.normals[i] = plane.normal->dot(towards) < 0.0f ? Eigen::Vector3f(-*plane.normal) : *plane.normal;
            }
            const double sum_d2 = static_cast<double>(d2[1]) + d2[2] + d2[3] + d2[4];
            map.radii_m[i] = static_cast<float>(std::sqrt(sum_d2 / 8.0));
        }
    });
    rep.degenerate_normals += static_cast<std::size_t>(std::count(normal_from.begin(), normal_from.end(), NormalFrom::degenerate));
    rep.scan_line_normals += static_cast<std::size_t>(std::count(normal_from.begin(), normal_from.end(), NormalFrom::scan_line));
}

}  // namespace

BackgroundMap load_background_map(const std::filesystem::path& file, const BackgroundOptions& options,
                                  BackgroundLoadReport* report) {
    const std::string name = file.string();
    BackgroundLoadReport local_report;
    BackgroundLoadReport& rep = report ? *report : local_report;
    rep = BackgroundLoadReport{};

    BackgroundMap map;
    map.source = name;
    std::vector<double> intensity;
    auto add = [&](const Eigen::Vector3d& p, std::optional<double> i) {
        if (!p.allFinite()) {
            ++rep.nonfinite_dropped;
            return;
        }
        map.points_world.push_back(options.scale * p + options.offset_m);
        if (i) intensity.push_back(std::isfinite(*i) ? std::max(*i, 0.0) : 0.0);
    };
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension == ".las") {
        const LasCloud las = read_las(file);
        map.points_world.reserve(las.points.size());
        for (std::size_t i = 0; i < las.points.size(); ++i) add(las.points[i], double(las.intensity[i]));
    } else if (!std::filesystem::is_regular_file(file)) {
        throw InputError(name, "(file)", "no such file");
    } else if (extension == ".ply") {
        const PlyVertices ply = read_ply(file);
        const std::optional<std::size_t> x = ply.property("x"), y = ply.property("y"), z = ply.property("z");
        if (!x || !y || !z) throw InputError(name, "element vertex", "needs properties x, y and z");
        const std::optional<std::size_t> i_property = ply.property("intensity");
        map.points_world.reserve(ply.count);
        for (std::size_t i = 0; i < ply.count; ++i)
            add(Eigen::Vector3d(ply.value(i, *x), ply.value(i, *y), ply.value(i, *z)),
                i_property ? std::optional<double>(ply.value(i, *i_property)) : std::nullopt);
    } else {
        const PcdCloud cloud = read_pcd(file);
        const std::size_t x = *cloud.field("x"), y = *cloud.field("y"), z = *cloud.field("z");
        const std::optional<std::size_t> i_field = cloud.field("intensity");
        map.points_world.reserve(cloud.points());
        for (std::uint64_t i = 0; i < cloud.points(); ++i) {
            add(Eigen::Vector3d(cloud.value(i, x), cloud.value(i, y), cloud.value(i, z)),
                i_field ? std::optional<double>(cloud.value(i, *i_field)) : std::nullopt);
        }
    }
    const std::size_t n = map.points_world.size();
    rep.points_loaded = n;
    if (n < 5) {
        throw InputError(name, "(file)", "has " + std::to_string(n) +
                                             " finite points; a background map needs at least 5 "
                                             "(four neighbours set each disc's size)");
    }

    // Geo-referenced coordinates (1e5..1e6 m) would lose centimetres in float: the k-d tree and
    // the plane fits work relative to the map's centroid.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : map.points_world) centre += p / static_cast<double>(n);
    std::optional<Eigen::Vector3d> scanner = options.scanner_position_m;
    if (options.heading_deg != 0.0) {
        const Eigen::AngleAxisd turn(options.heading_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ());
        const auto turned = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return centre + turn * (p - centre); };
        for (auto& p : map.points_world) p = turned(p);
        if (scanner) scanner = turned(*scanner);
    }
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    cloud->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3f q = (map.points_world[i] - centre).cast<float>();
        (*cloud)[i] = pcl::PointXYZ(q.x(), q.y(), q.z());
    }
    estimate_discs(*cloud, options.normal_neighbours, scanner, map, rep);

    std::vector<float> sorted = map.radii_m;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2), sorted.end());
    const float median = sorted[n / 2];
    const float lo = static_cast<float>(kMinRadiusOfMedian) * median;
    const float hi = static_cast<float>(kMaxRadiusOfMedian) * median;
    for (float& r : map.radii_m) {
        if (r < lo || r > hi) {
            r = std::clamp(r, lo, hi);
            ++rep.radii_clamped;
        }
    }

    const double i_max = intensity.empty() ? 0.0 : *std::max_element(intensity.begin(), intensity.end());
    if (!options.reflectance && i_max > 0.0) {
        rep.reflectance_from_intensity = true;
        map.reflectance.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            map.reflectance[i] = static_cast<float>(
                options.reflectance_per_intensity ? std::min(1.0, *options.reflectance_per_intensity * intensity[i])
                                                  : options.reflectance_at_max_intensity * intensity[i] / i_max);
        }
    } else {
        if (!options.reflectance && !intensity.empty()) {
            spdlog::warn("{}: every intensity is zero; using reflectance {}", name, kDefaultReflectance);
        }
        map.reflectance.assign(n, static_cast<float>(options.reflectance.value_or(kDefaultReflectance)));
    }

    if (rep.nonfinite_dropped > 0) spdlog::warn("{}: dropped {} non-finite points", name, rep.nonfinite_dropped);
    if (rep.degenerate_normals > 0) {
        spdlog::warn("{}: {} points have no plane of neighbours; their normals are set to {}", name,
                     rep.degenerate_normals, options.scanner_position_m ? "face the scanner" : "+z");
    }
    if (rep.scan_line_normals > 0) {
        spdlog::info("{}: {} points lie on scan lines seen edge-on; their discs face the scanner", name,
                     rep.scan_line_normals);
    }
    spdlog::info("{}: {} background points, median disc radius {:.3f} m", name, n, median);
    return map;
}

}  // namespace ladarsim::scene
