#pragma once
// A footprint on one plane, as its probes tell: integrated over fixed directions, with no ray.
#include <vector>

#include <Eigen/Core>

#include "curved_patch.h"
#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"

namespace ladarsim::sensor_model {

class PlanePatch final : public FootprintStrategy {
public:
    /// Where the probes' points leave every plane by more than the receiver's resolution, `curved`
    /// is asked instead.
    PlanePatch(const FootprintContext& context, const CurvedPatch& curved);

    /// The part outside part.excluded (carrying part.share of the beam) as one plane, from the
    /// probes outside it: empty where none met anything, parted where some met nothing or another
    /// object, declined where they do not make one plane (or one curved surface).
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;

private:
    const FootprintContext& context_;
    const CurvedPatch& curved_;
    std::vector<Eigen::Vector3d> quadrature_in_beam_;  ///< directions integrating the plane
    std::vector<double> quadrature_x_, quadrature_y_;
    /// The range variance over the footprint per that over the nodes (Footprint::variance_over_fixed).
    double within_cells_ = 1.0;
};

}  // namespace ladarsim::sensor_model
