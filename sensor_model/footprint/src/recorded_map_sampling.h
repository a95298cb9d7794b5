#pragma once
// A footprint over a recorded map, by brute force: its discs overlap and tilt at random, so cells
// never agree and refinement would pay its bookkeeping for every sub-ray up to its budget
// (docs/sensor.md, "Footprint and returns").
#include <span>

#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"
#include "map_scanline.h"
#include "stratified_sub_rays.h"

namespace ladarsim::sensor_model {

class RecordedMapSampling final : public FootprintStrategy {
public:
    /// Its own stratified sub-rays at the outline budget (context.outline_samples).
    explicit RecordedMapSampling(const FootprintContext& context);

    /// Without media, the map's discs integrated along lines instead of any sub-rays (null: the
    /// sub-rays). Set before rendering.
    void integrate_along_lines(const MapScanline* lines) { lines_ = lines; }
    /// Whether the witnesses inside the footprint met the recorded map.
    bool met_by(std::span<const Probe* const> witnesses) const;

    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;

private:
    const FootprintContext& context_;
    StratifiedSubRays own_;
    const MapScanline* lines_ = nullptr;
};

}  // namespace ladarsim::sensor_model
