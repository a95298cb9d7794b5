#include "recorded_map_sampling.h"

#include <algorithm>

#include "ladarsim/core/units.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::sensor_model {

RecordedMapSampling::RecordedMapSampling(const FootprintContext& context)
    : context_(context),
      own_(context, Footprint(context.sensor.transmitter.divergence_mrad * kMrad, static_cast<int>(context.outline_samples),
                              context.settings.truncation)) {}

bool RecordedMapSampling::met_by(std::span<const Probe* const> witnesses) const {
    const Footprint& footprint = context_.shape.footprint();
    return std::any_of(witnesses.begin(), witnesses.end(), [&](const Probe* p) {
        return p->hit->hit && p->hit->hit->object_id == scene::kBackgroundObjectId && footprint.within_truncation(p->x_rad, p->y_rad);
    });
}

Integration RecordedMapSampling::integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const {
    if (lines_ && !beam.media) return lines_->integrate(beam, part, out);
    return own_.integrate(beam, part, out);
}

}  // namespace ladarsim::sensor_model
