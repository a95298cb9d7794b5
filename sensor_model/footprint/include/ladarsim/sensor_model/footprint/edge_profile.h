#pragma once
// How the echo of one side of a straight edge across a footprint spreads in range (docs/sensor.md,
// "Footprint and returns", step 3).
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace ladarsim::sensor_model {

/// A point of a footprint (its offset, radians, footprint coordinates) and the range it met.
struct RangeSample {
    Eigen::Vector2d offset;
    double range_m;
};

/// One side of a straight chord across a footprint: the offsets o with normal . o > distance
/// (`beyond`), or the others.
struct ChordSide {
    Eigen::Vector2d normal;  ///< unit
    double distance;
    bool beyond;
};

/// A slice of one side of a footprint between two ranges.
struct RangeSlice {
    Eigen::Vector2d offset;  ///< its middle
    double range_m;
    double share;     ///< of the side's energy: the slices' shares sum to 1
    double spread_m;  ///< standard deviation of the range across it
};

/// A plane's range over a footprint, linear in the offset (radians): at_axis_m + per_rad . offset.
struct RangePlane {
    double at_axis_m;
    Eigen::Vector2d per_rad;
};

/// The plane fitted to a side's points (least squares); none where they are fewer than four, do
/// not span the footprint in two directions (a tenth of `max_offset_rad` across every direction),
/// or leave the plane by more than `tolerance_m` (RMS).
std::optional<RangePlane> fit_range_plane(std::span<const RangeSample> samples, double max_offset_rad, double tolerance_m);

/// The range profile of one side of a footprint (a round Gaussian of per-axis sigma `sigma_rad`
/// truncated at `max_offset_rad`) on `plane`: the Gaussian's exact mass on the side along 128 lines
/// of constant range (an error function across each), grouped into slices `resolution_m` deep where
/// the side is densest and holding as much mass elsewhere (deeper in its tails, at most an eighth of
/// the footprint's depth: an infinite resolution gives eight). Where a straight edge cuts the
/// footprint across its range gradient (a crest against what lies behind it, seen at grazing
/// incidence), the side's echo ends sharply at the edge, where the beam is brightest: one pulse
/// stretched by the side's spread misplaces that peak. Appends the slices to `out`; false, nothing
/// appended, where the side holds none of the Gaussian.
bool range_profile(const RangePlane& plane, const ChordSide& side, double max_offset_rad, double sigma_rad, double resolution_m,
                   std::vector<RangeSlice>& out);

}  // namespace ladarsim::sensor_model
