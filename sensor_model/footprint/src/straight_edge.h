#pragma once
// A footprint parted by one straight edge into two surfaces (one may be nothing): a skyline, a
// wall against the ground, a roof's eave.
#include <span>
#include <vector>

#include <Eigen/Core>

#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/edge_profile.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"

namespace ladarsim::sensor_model {

/// The rim of the footprint is sampled for the edge's two ends (each then bisected), every probe
/// must lie on its surface's side of the chord between them, and each surface takes the beam's
/// exact share beyond or before the chord (a closed form of the truncated Gaussian), spread over
/// an equal-energy quadrature on its side. Declined (nothing appended) where that does not hold: a
/// corner, a curved edge, more surfaces. For a whole footprint without media or targets.
class StraightEdge final : public FootprintStrategy {
public:
    explicit StraightEdge(const FootprintContext& context);

    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;

    /// Replaces one surface's echoes in `out` (from `first` on: `share` of the beam, their points
    /// `samples` spreading `spread_m` in range) by the range profile of the plane those lie on
    /// over `side` of the footprint (edge_profile.h), their energy kept; nothing changes where
    /// they do not lie on one plane.
    void profile_in_range(const BeamAim& aim, std::span<const RangeSample> samples, const ChordSide& side, double share,
                          double spread_m, std::size_t first, BeamEchoes& out) const;

    const FootprintContext& context() const { return context_; }
    /// Equal-energy cells spreading each side's share.
    std::span<const Eigen::Vector2d> quadrature() const { return quadrature_; }

private:
    const FootprintContext& context_;
    std::vector<Eigen::Vector2d> quadrature_;
};

}  // namespace ladarsim::sensor_model
