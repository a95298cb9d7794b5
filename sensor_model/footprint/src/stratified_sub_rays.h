#pragma once
// Brute force: one sub-ray in each of a footprint's stratified cells of equal energy.
#include <cstdint>
#include <optional>
#include <span>

#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"

namespace ladarsim::sensor_model {

class StratifiedSubRays final : public FootprintStrategy {
public:
    /// `cells`: the footprint's stratification (its number of cells is the number of sub-rays).
    StratifiedSubRays(const FootprintContext& context, Footprint cells) : context_(context), cells_(std::move(cells)) {}

    /// One sub-ray in each cell (jittered when the render is, by draws from part.first_draw on) outside
    /// part.excluded, those then carrying part.share of the beam. (part.rect is the whole footprint.)
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;

private:
    /// Traces sub-rays, appending their echoes (media draws from 64 x `first_draw` on).
    void trace(const BeamSetting& beam, std::span<const SubRay> sub_rays, BeamEchoes& out, std::uint32_t first_draw) const;

    const FootprintContext& context_;
    Footprint cells_;
};

}  // namespace ladarsim::sensor_model
