#include "ladarsim/detect/clustering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "neighbours_within.h"

namespace ladarsim::detect {
namespace {

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
    const std::vector<std::vector<int>> neighbours = neighbours_within(points, radius_m);
    std::vector<int> parent(points.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
        for (int j : neighbours[static_cast<std::size_t>(i)]) {
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

double acquisition_range_m(const Points& points) {
    if (points.empty()) return 0.0;
    std::vector<float> ranges;
    ranges.reserve(points.size());
    for (const auto& p : points) ranges.push_back(p.norm());
    const auto k = static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(ranges.size() - 1));
    std::nth_element(ranges.begin(), ranges.begin() + k, ranges.end());
    return ranges[static_cast<std::size_t>(k)];
}

Points remove_outliers(const Points& points, double radius_m, int min_neighbours) {
    // As PCL's RadiusOutlierRemoval over a dense cloud decides: a point stays when its
    // (min_neighbours + 1)-th nearest, itself first, lies within the radius (squared, in double).
    // FLANN's radius search keeps what lies strictly inside its float radius: searched a float
    // step wider, then held to that test.
    const double radius2 = radius_m * radius_m;
    const float wider = std::nextafter(std::nextafter(static_cast<float>(radius2), std::numeric_limits<float>::infinity()),
                                       std::numeric_limits<float>::infinity());
    std::vector<std::vector<float>> squared;
    neighbours_within(points, std::sqrt(static_cast<double>(wider)), &squared);
    Points out;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto within = std::count_if(squared[i].begin(), squared[i].end(), [&](float d2) { return static_cast<double>(d2) <= radius2; });
        if (within >= min_neighbours + 1) out.push_back(points[i]);
    }
    return out;
}

Points remove_incoherent(const Points& points, double radius_m, double tolerance_m, int min_neighbours) {
    if (points.empty()) return points;
    const std::vector<std::vector<int>> neighbours_of = neighbours_within(points, radius_m);
    std::vector<double> ranges(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) ranges[i] = points[i].cast<double>().norm();
    Points out;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::vector<int>& neighbours = neighbours_of[i];
        const auto agreeing = std::count_if(neighbours.begin(), neighbours.end(), [&](int j) {
            return static_cast<std::size_t>(j) != i && std::abs(ranges[static_cast<std::size_t>(j)] - ranges[i]) <= tolerance_m;
        });
        if (agreeing >= min_neighbours) out.push_back(points[i]);
    }
    return out;
}

Points without_volume_echoes(const Points& points, double pitch_rad, double tolerance_m, double window_m) {
    if (points.empty()) return points;
    // Directions as points on the unit sphere: beams a pitch apart lie a pitch apart there.
    Points directions;
    directions.reserve(points.size());
    std::vector<double> ranges(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        ranges[i] = points[i].cast<double>().norm();
        directions.push_back(points[i] / static_cast<float>(ranges[i]));
    }
    std::vector<std::vector<float>> squared_of;
    const std::vector<std::vector<int>> neighbours_of = neighbours_within(directions, 1.5 * pitch_rad, &squared_of);
    Points out;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::vector<int>& neighbours = neighbours_of[i];
        const std::vector<float>& squared = squared_of[i];
        bool echo_train = false, beside = false;
        for (std::size_t k = 0; k < neighbours.size(); ++k) {
            const auto j = static_cast<std::size_t>(neighbours[k]);
            if (j == i) continue;
            const double dr = std::abs(ranges[j] - ranges[i]);
            if (std::sqrt(squared[k]) < 0.5 * pitch_rad) echo_train = echo_train || dr <= window_m;
            else beside = beside || dr <= tolerance_m;
        }
        if (!echo_train || beside) out.push_back(points[i]);
    }
    return out;
}

Cluster without_sparse_lines(const Cluster& cluster, double line_pitch_rad, double min_fraction, const std::vector<float>& intensity) {
    std::vector<std::pair<double, std::size_t>> elevation;
    for (std::size_t i = 0; i < cluster.points.size(); ++i) {
        const Eigen::Vector3d p = cluster.points[i].cast<double>();
        elevation.emplace_back(std::atan2(p.z(), p.head<2>().norm()), i);
    }
    std::sort(elevation.begin(), elevation.end());
    std::vector<std::size_t> line_of(cluster.points.size());
    std::vector<std::size_t> line_size;
    for (std::size_t k = 0; k < elevation.size(); ++k) {
        if (k == 0 || elevation[k].first - elevation[k - 1].first > 0.5 * line_pitch_rad) line_size.push_back(0);
        line_of[elevation[k].second] = line_size.size() - 1;
        ++line_size.back();
    }
    if (line_size.size() < 2) return cluster;
    const auto fullest_line = static_cast<std::size_t>(std::max_element(line_size.begin(), line_size.end()) - line_size.begin());
    const double fullest = static_cast<double>(line_size[fullest_line]);
    std::vector<bool> kept_line(line_size.size());
    for (std::size_t l = 0; l < line_size.size(); ++l) kept_line[l] = static_cast<double>(line_size[l]) >= min_fraction * fullest;
    if (intensity.size() == cluster.points.size()) {
        // Azimuths about the fullest line's first return, so that a cluster straddling +-pi is whole.
        std::size_t first = 0;
        while (line_of[first] != fullest_line) ++first;
        const double reference_az = std::atan2(cluster.points[first].y(), cluster.points[first].x());
        std::vector<double> azimuth(cluster.points.size());
        for (std::size_t i = 0; i < cluster.points.size(); ++i)
            azimuth[i] = std::remainder(std::atan2(cluster.points[i].y(), cluster.points[i].x()) - reference_az, 2.0 * std::numbers::pi);
        std::vector<double> low(line_size.size(), std::numeric_limits<double>::infinity()), high(line_size.size(), -std::numeric_limits<double>::infinity());
        std::vector<double> elevation_sum(line_size.size(), 0.0);
        std::vector<std::vector<float>> echoes(line_size.size());
        for (const auto& [e, i] : elevation) {
            low[line_of[i]] = std::min(low[line_of[i]], azimuth[i]);
            high[line_of[i]] = std::max(high[line_of[i]], azimuth[i]);
            elevation_sum[line_of[i]] += e;
            echoes[line_of[i]].push_back(intensity[i]);
        }
        const float fullest_peak = *std::max_element(echoes[fullest_line].begin(), echoes[fullest_line].end());
        const auto mean_elevation = [&](std::size_t l) { return elevation_sum[l] / static_cast<double>(line_size[l]); };
        const std::vector<bool> full_line = kept_line;
        for (std::size_t l = 0; l < line_size.size(); ++l) {
            if (full_line[l] || low[l] < low[fullest_line] || high[l] > high[fullest_line]) continue;
            // A fringe line's typical echo (its lower median: one glint does not move it) is
            // weaker than the line nearest the target's strongest.
            const auto lower_middle = echoes[l].begin() + static_cast<std::ptrdiff_t>((echoes[l].size() - 1) / 2);
            std::nth_element(echoes[l].begin(), lower_middle, echoes[l].end());
            // A target lower than a line pitch reaches the fringe of the lines beside the one or
            // two that see it fully, no further: where two do, it lies between them, and a third
            // line is 1.5 pitches off it (the paper's raster: a beam's weight there is 1e-4 of its
            // peak).
            bool beside_every_full_line = true;
            for (std::size_t f = 0; f < line_size.size(); ++f)
                if (full_line[f]) beside_every_full_line = beside_every_full_line && std::abs(mean_elevation(l) - mean_elevation(f)) <= 1.5 * line_pitch_rad;
            kept_line[l] = *lower_middle < fullest_peak && beside_every_full_line;
        }
    }
    Cluster out;
    for (std::size_t i = 0; i < cluster.points.size(); ++i)
        if (kept_line[line_of[i]]) out.points.push_back(cluster.points[i]);
    if (out.points.size() == cluster.points.size()) return cluster;
    out.box = bounding_box(out.points);
    return out;
}

bool small_enough(const Cluster& cluster, double max_diagonal_m, double beam_spread_rad) {
    return cluster.box.size.norm() <= max_diagonal_m + beam_spread_rad * cluster.box.centre.norm();
}

std::vector<Cluster> plausible_targets(std::vector<Cluster> clusters, double max_diagonal_m, double beam_spread_rad,
                                       std::size_t min_points) {
    std::erase_if(clusters, [&](const Cluster& c) { return !small_enough(c, max_diagonal_m, beam_spread_rad) || c.points.size() < min_points; });
    return clusters;
}

std::vector<Cluster> beam_connected(const Cluster& cluster, double az_pitch_rad, double el_pitch_rad) {
    struct Direction {
        double azimuth, elevation;
        std::size_t index;
    };
    std::vector<Direction> directions;
    for (std::size_t i = 0; i < cluster.points.size(); ++i) {
        const Eigen::Vector3d p = cluster.points[i].cast<double>();
        directions.push_back({std::atan2(p.y(), p.x()), std::atan2(p.z(), p.head<2>().norm()), i});
    }
    std::sort(directions.begin(), directions.end(), [](const Direction& a, const Direction& b) { return a.azimuth < b.azimuth; });
    std::vector<int> parent(directions.size());
    std::iota(parent.begin(), parent.end(), 0);
    // Neighbours: the same or the next line, at most two beams apart along it (one beam missed).
    const double max_az = 2.5 * az_pitch_rad, max_el = 1.5 * el_pitch_rad;
    for (std::size_t i = 0; i < directions.size(); ++i)
        for (std::size_t j = i + 1; j < directions.size() && directions[j].azimuth - directions[i].azimuth <= max_az; ++j)
            if (std::abs(directions[j].elevation - directions[i].elevation) <= max_el) {
                const int a = find(parent, static_cast<int>(i)), b = find(parent, static_cast<int>(j));
                if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
            }
    // Pieces in the order of their first point in the cluster, points in the cluster's order.
    std::vector<std::size_t> root_of(cluster.points.size());
    for (std::size_t k = 0; k < directions.size(); ++k) root_of[directions[k].index] = static_cast<std::size_t>(find(parent, static_cast<int>(k)));
    std::vector<Cluster> pieces;
    std::vector<long> piece_of(directions.size(), -1);
    for (std::size_t i = 0; i < cluster.points.size(); ++i) {
        long& piece = piece_of[root_of[i]];
        if (piece < 0) {
            piece = static_cast<long>(pieces.size());
            pieces.emplace_back();
        }
        pieces[static_cast<std::size_t>(piece)].points.push_back(cluster.points[i]);
    }
    for (Cluster& c : pieces) c.box = bounding_box(c.points);
    return pieces;
}

std::vector<Cluster> coherent_cores(const std::vector<Cluster>& clusters, double tolerance_m, std::size_t min_points) {
    std::vector<Cluster> cores;
    std::vector<std::pair<double, std::size_t>> ranges;
    for (const Cluster& c : clusters) {
        ranges.clear();
        for (std::size_t i = 0; i < c.points.size(); ++i) ranges.emplace_back(c.points[i].cast<double>().norm(), i);
        std::sort(ranges.begin(), ranges.end());
        // The window [ranges[first], ranges[first] + 2 tolerance] holding the most returns (the
        // first such, so the result does not depend on anything but the points).
        std::size_t best_first = 0, best_count = 0;
        for (std::size_t first = 0, end = 0; first < ranges.size(); ++first) {
            end = std::max(end, first);
            while (end < ranges.size() && ranges[end].first <= ranges[first].first + 2.0 * tolerance_m) ++end;
            if (end - first > best_count) {
                best_count = end - first;
                best_first = first;
            }
        }
        if (best_count < min_points) continue;
        Cluster core;
        if (best_count == c.points.size()) {
            core = c;
        } else {
            // In the cluster's own order, so that cores of unchanged clusters are unchanged.
            std::vector<std::size_t> kept;
            for (std::size_t k = best_first; k < best_first + best_count; ++k) kept.push_back(ranges[k].second);
            std::sort(kept.begin(), kept.end());
            for (std::size_t i : kept) core.points.push_back(c.points[i]);
            core.box = bounding_box(core.points);
        }
        cores.push_back(std::move(core));
    }
    return cores;
}

std::vector<Cluster> standing_clear(std::vector<Cluster> clusters, const Points& all, double margin_m, double max_ratio) {
    std::erase_if(clusters, [&](const Cluster& c) {
        const Eigen::Vector3f half = (0.5 * c.box.size).cast<float>() + Eigen::Vector3f::Constant(static_cast<float>(margin_m));
        const Eigen::Vector3f centre = c.box.centre.cast<float>();
        const auto inside = std::count_if(all.begin(), all.end(), [&](const Eigen::Vector3f& p) {
            return ((p - centre).cwiseAbs().array() <= half.array()).all();
        });
        const auto others = static_cast<double>(inside) - static_cast<double>(c.points.size());
        return others > max_ratio * static_cast<double>(c.points.size());
    });
    return clusters;
}

std::vector<Cluster> range_coherent(std::vector<Cluster> clusters, double tolerance_m, double min_fraction) {
    std::erase_if(clusters, [&](const Cluster& c) {
        if (c.points.empty()) return true;
        std::vector<double> ranges;
        ranges.reserve(c.points.size());
        for (const auto& p : c.points) ranges.push_back(p.cast<double>().norm());
        const auto middle = ranges.begin() + static_cast<std::ptrdiff_t>(ranges.size() / 2);
        std::nth_element(ranges.begin(), middle, ranges.end());
        const double median = *middle;
        const auto agreeing = std::count_if(ranges.begin(), ranges.end(), [&](double r) { return std::abs(r - median) <= tolerance_m; });
        return static_cast<double>(agreeing) < min_fraction * static_cast<double>(ranges.size());
    });
    return clusters;
}

}  // namespace ladarsim::detect
