#pragma once
// A footprint over a recorded map integrated along lines instead of sampled by sub-rays
// (docs/sensor.md, "Footprint and returns"): the
// footprint is cut into strips of equal energy across its azimuth offset; on each strip's line
// every disc the line's plane cuts is a chord, and the visible surface is the nearest chord at each
// point (the ray tracer's nearest-disc rule). Each visible piece carries the beam's Gaussian
// weight over it and the range equation of its disc, stretched over its range span. Other objects
// (a static mesh beyond the map, a target in front of it) are found by rays: the strategy alone
// does not know them.
#include <cstdint>
#include <vector>

#include "beam_cone.h"
#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"
#include "ladarsim/sensor_model/footprint/disc_chords.h"
#include "map_discs.h"

namespace ladarsim::sensor_model {

class MapScanline final : public FootprintStrategy {
public:
    /// `lines` strips across the footprint. `rays_per_line` > 0: that many rays on each line, in
    /// cells of equal energy, find whatever other object covers their cell nearer than the map (or
    /// where the map leaves a gap); 0: one ray in the middle of each gap the map leaves on a line,
    /// for what lies beyond it (targets in front of the map are the caller's: FootprintPart::excluded).
    /// With `cone` (and rays_per_line > 0), the cells over the outline of the targets the beam's
    /// cone meets are split until they are as fine across the line as the lines are apart.
    MapScanline(const FootprintContext& context, const MapDiscs& discs, int lines, int rays_per_line, const BeamCone* cone = nullptr);

    /// The echoes of the map (and of what its rays met) over `part` outside part.excluded, carrying
    /// part.share of the beam. Declined in media (the map's rays do not scatter).
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;

private:
    struct Line {
        double x_rad, X, y_max_rad, t_max, weight;
    };

    /// Every candidate disc's chord on each line its sphere spans in azimuth (beam frame `R`, the
    /// beam leaving `apex`, relative to the discs' origin).
    void chords_on_lines(const Eigen::Matrix3d& R, const Eigen::Vector3d& apex, std::vector<std::vector<DiscChord>>& on_line) const;
    /// Per line, the visible pieces over `part` (outside its excluded rectangle; lower_envelope
    /// orders each line's chords), line k's from line_start[k] to line_start[k + 1]. Returns the
    /// beam's weight over the part.
    double visible_pieces(std::vector<std::vector<DiscChord>>& on_line, const FootprintPart& part,
                          std::vector<VisiblePiece>& pieces, std::vector<std::uint32_t>& line_start) const;
    /// The footprint's y offset of a line's tangent coordinate t.
    double y_of(double t) const;
    /// The beam's weight on `line` between tangent coordinates ta and tb.
    double mass(const Line& line, double ta, double tb) const;

    const FootprintContext& context_;
    const MapDiscs& discs_;
    const BeamCone* cone_;
    int rays_per_line_;
    int dense_split_;  ///< cells a coarse cell over a target's outline is split into
    std::vector<Line> lines_;
    double tan_half_;  ///< the truncated footprint's cone, as tan of its half-angle
};

}  // namespace ladarsim::sensor_model
