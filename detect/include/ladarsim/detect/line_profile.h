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

/// The elevation (sensor frame, radians) of a small target seen by more than one scan line, from
/// the strongest echo of its two strongest lines: a Gaussian beam of 1/e^2 intensity radius
/// `beam_radius_rad` across lines e1 and e2 with peaks s1 and s2 puts it at
/// (e1 + e2) / 2 + beam_radius^2 ln(s1 / s2) / (4 (e1 - e2)), clamped between them. Lines are told
/// apart as in without_sparse_lines (a gap in elevation over half `line_pitch_rad`). Empty, so the
/// caller keeps the midpoint of its returns, when they lie on one line, when the two strongest lines
/// are not neighbours, or when their peaks differ by less than `min_peak_ratio`: a small target's
/// echo fluctuates from line to line (its facets' speckle, a line scanned 1 ms after the other),
/// by up to 2.2 times where dataset 4's drone lies midway between lines at 1.9 km.
std::optional<double> target_elevation_rad(const Points& points, const std::vector<float>& intensity,
                                           double line_pitch_rad, double beam_radius_rad, double min_peak_ratio);

/// `centre` moved to elevation `elevation_rad` about the sensor origin, its range and azimuth kept.
Eigen::Vector3d at_elevation(const Eigen::Vector3d& centre, double elevation_rad);

}  // namespace ladarsim::detect
