#include "ladarsim/detect/line_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>

namespace ladarsim::detect {

IntensityOf::IntensityOf(const Points& points, const std::vector<float>& intensity) {
    if (intensity.size() != points.size()) throw std::invalid_argument("IntensityOf: one intensity per point needed");
    by_position_.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) by_position_.emplace(points[i], intensity[i]);
}

std::size_t IntensityOf::Hash::operator()(const Eigen::Vector3f& p) const {
    std::size_t h = 0;
    for (int i = 0; i < 3; ++i) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &p[i], sizeof bits);
        h = h * 1000003u ^ std::hash<std::uint32_t>{}(bits);
    }
    return h;
}

float IntensityOf::operator()(const Eigen::Vector3f& p) const {
    const auto it = by_position_.find(p);
    return it == by_position_.end() ? 0.0f : it->second;
}

std::optional<LinePair> strongest_line_pair(const Points& points, const std::vector<float>& intensity, double line_pitch_rad) {
    struct Echo {
        double elevation;
        double intensity;
    };
    std::vector<Echo> echoes;
    for (std::size_t i = 0; i < points.size() && i < intensity.size(); ++i) {
        const Eigen::Vector3d p = points[i].cast<double>();
        echoes.push_back({std::atan2(p.z(), p.head<2>().norm()), intensity[i]});
    }
    std::sort(echoes.begin(), echoes.end(), [](const Echo& a, const Echo& b) { return a.elevation < b.elevation; });
    std::vector<Echo> peaks;
    for (std::size_t i = 0; i < echoes.size(); ++i) {
        if (i == 0 || echoes[i].elevation - echoes[i - 1].elevation > 0.5 * line_pitch_rad) peaks.push_back(echoes[i]);
        else if (echoes[i].intensity > peaks.back().intensity) peaks.back() = echoes[i];
    }
    if (peaks.size() < 2) return std::nullopt;
    std::partial_sort(peaks.begin(), peaks.begin() + 2, peaks.end(), [](const Echo& a, const Echo& b) { return a.intensity > b.intensity; });
    const auto [lower, upper] = std::minmax(peaks[0], peaks[1], [](const Echo& a, const Echo& b) { return a.elevation < b.elevation; });
    if (upper.elevation - lower.elevation > 1.5 * line_pitch_rad || !(lower.intensity > 0.0) || !(upper.intensity > 0.0))
        return std::nullopt;
    return LinePair{lower.elevation, upper.elevation, std::log(upper.intensity / lower.intensity)};
}

double elevation_between(const LinePair& pair, double log_ratio, double beam_radius_rad) {
    const double e = 0.5 * (pair.lower_rad + pair.upper_rad) +
                     beam_radius_rad * beam_radius_rad * log_ratio / (4.0 * (pair.upper_rad - pair.lower_rad));
    return std::clamp(e, pair.lower_rad, pair.upper_rad);
}

Eigen::Vector3d at_elevation(const Eigen::Vector3d& centre, double elevation_rad) {
    const double range = centre.norm();
    const double azimuth = std::atan2(centre.y(), centre.x());
    return range * Eigen::Vector3d(std::cos(elevation_rad) * std::cos(azimuth), std::cos(elevation_rad) * std::sin(azimuth),
                                   std::sin(elevation_rad));
}

}  // namespace ladarsim::detect
