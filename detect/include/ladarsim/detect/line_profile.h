#pragma once
// Where a small target lies between two scan lines, from the footprint's profile across them. A
// target smaller than the line pitch is reported by the beams of the lines whose footprints
// reach it, at the lines' elevations: the box around its returns is centred between the lines
// whatever its true height (0.07 m above a 6 cm drone at 600 m when the gimbal lags it). Each
// line's strongest echo samples the beam's Gaussian profile at the target's offset from that line,
// so the two lines' peaks say where between them it lies.
#include <optional>
#include <unordered_map>
#include <vector>

#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

/// Intensities of a frame's returns, found by position (clustering copies positions only; a
/// frame's returns have distinct positions). 0 for a position the frame does not hold.
class IntensityOf {
public:
    IntensityOf(const Points& points, const std::vector<float>& intensity);
    float operator()(const Eigen::Vector3f& p) const;
    bool empty() const { return by_position_.empty(); }

private:
    struct Hash {
        std::size_t operator()(const Eigen::Vector3f& p) const;
    };
    std::unordered_map<Eigen::Vector3f, float, Hash> by_position_;
};

/// The two neighbouring scan lines with the strongest echoes of a small target: their elevations
/// (sensor frame, radians) and the log of the upper line's peak echo over the lower's. Each line's
/// peak is its beam nearest the target in azimuth, the beam's profile sampled at the target's
/// offset from the line. Lines are told apart as in without_sparse_lines (a gap in elevation over
/// half `line_pitch_rad`). Empty when the returns lie on one line or the two strongest lines are
/// not neighbours.
struct LinePair {
    double lower_rad = 0.0;
    double upper_rad = 0.0;
    double log_ratio = 0.0;  ///< ln(upper peak / lower peak)
};
std::optional<LinePair> strongest_line_pair(const Points& points, const std::vector<float>& intensity, double line_pitch_rad);

/// Where between the pair's lines a point target lies for a log peak ratio `log_ratio` under a
/// Gaussian beam of 1/e^2 intensity radius `beam_radius_rad`:
/// (lower + upper) / 2 + beam_radius^2 log_ratio / (4 (upper - lower)), clamped between them.
double elevation_between(const LinePair& pair, double log_ratio, double beam_radius_rad);

/// `centre` moved to elevation `elevation_rad` about the sensor origin, its range and azimuth kept.
Eigen::Vector3d at_elevation(const Eigen::Vector3d& centre, double elevation_rad);

}  // namespace ladarsim::detect
