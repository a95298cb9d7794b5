#include "ladarsim/detect/clustering.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <pcl/filters/radius_outlier_removal.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace ladarsim::detect {
namespace {

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const Points& points) {
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    cloud->reserve(points.size());
    for (const auto& p : points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    return cloud;
}

int find(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
        parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        i = parent[static_cast<std::size_t>(i)];
    }
    return i;
}

}  // namespace

std::vector<Cluster> rbnn(const Points& points, double radius_m) {
    std::vector<Cluster> clusters;
    if (points.empty()) return clusters;
    const auto cloud = to_pcl(points);
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
    std::vector<int> parent(points.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<int> neighbours;
    std::vector<float> distances;
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
        tree.radiusSearch((*cloud)[static_cast<std::size_t>(i)], radius_m, neighbours, distances);
        for (int j : neighbours) {
            const int a = find(parent, i), b = find(parent, j);
            if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
        }
    }
    std::vector<int> cluster_of(points.size(), -1);
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
        const int root = find(parent, i);
        if (cluster_of[static_cast<std::size_t>(root)] < 0) {
            cluster_of[static_cast<std::size_t>(root)] = static_cast<int>(clusters.size());
            clusters.emplace_back();
        }
        clusters[static_cast<std::size_t>(cluster_of[static_cast<std::size_t>(root)])].points.push_back(points[static_cast<std::size_t>(i)]);
    }
    for (auto& c : clusters) c.box = bounding_box(c.points);
    // Largest first; ties keep the order of their first point, so the result is deterministic.
    std::stable_sort(clusters.begin(), clusters.end(),
                     [](const Cluster& a, const Cluster& b) { return a.points.size() > b.points.size(); });
    return clusters;
}

double vrbnn_radius_m(double lambda, const SensorGeometry& sensor, double range_m, double bias_m) {
    const double fov_rad = std::min(sensor.field_az_deg, sensor.field_el_deg) * std::numbers::pi / 180.0;
    const double beams = static_cast<double>(sensor.beams_az) * sensor.beams_el;
    return lambda / beams * std::tan(fov_rad) * range_m + bias_m;
}

double default_lambda(const SensorGeometry& sensor) {
    const double pitch_deg = std::max(sensor.field_az_deg / sensor.beams_az, sensor.field_el_deg / sensor.beams_el);
    const double slope = 1.2 * pitch_deg * std::numbers::pi / 180.0;
    return slope / vrbnn_radius_m(1.0, sensor, 1.0, 0.0);
}

Points remove_outliers(const Points& points, double radius_m, int min_neighbours) {
    if (points.empty()) return points;
    const auto cloud = to_pcl(points);
    pcl::RadiusOutlierRemoval<pcl::PointXYZ> filter;
    filter.setInputCloud(cloud);
    filter.setRadiusSearch(radius_m);
    filter.setMinNeighborsInRadius(min_neighbours);
    pcl::Indices kept;
    filter.filter(kept);
    Points out;
    out.reserve(kept.size());
    for (auto i : kept) out.push_back(points[static_cast<std::size_t>(i)]);
    return out;
}

std::vector<Cluster> plausible_targets(std::vector<Cluster> clusters, double max_diagonal_m, double beam_spread_rad,
                                       std::size_t min_points) {
    std::erase_if(clusters, [&](const Cluster& c) {
        return c.box.size.norm() > max_diagonal_m + beam_spread_rad * c.box.centre.norm() || c.points.size() < min_points;
    });
    return clusters;
}

}  // namespace ladarsim::detect
