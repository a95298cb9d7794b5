#pragma once
// A footprint on one curved or folded surface (grazing terrain), as its probes tell: integrated on
// the probes' facets (fit_curved_patch), with no ray.
#include <vector>

#include "footprint_context.h"
#include "patch_probes.h"
#include "ladarsim/sensor_model/footprint/curved_patch_fit.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"

namespace ladarsim::sensor_model {

class CurvedPatch final : public FootprintStrategy {
public:
    explicit CurvedPatch(const FootprintContext& context);

    /// The part outside part.excluded (carrying part.share of the beam) as one surface, where its
    /// probes all met one object that is not a recorded map (whose structure in range is what its
    /// sub-rays are for), make one surface in range order and share one material; declined else.
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;
    /// The same from the probes that speak for the part, gathered already (a plane patch's, which
    /// asks this where its probes leave every plane).
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, const PatchProbes& probes, BeamEchoes& out) const;

private:
    const FootprintContext& context_;
    std::vector<PatchNode> nodes_;  ///< directions integrating the patch
    /// The range spread over the footprint per that over the nodes (Footprint::variance_over_fixed, its root).
    double spread_scale_ = 1.0;
};

}  // namespace ladarsim::sensor_model
