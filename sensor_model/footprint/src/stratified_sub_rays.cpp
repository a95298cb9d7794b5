#include "stratified_sub_rays.h"

#include <cmath>
#include <vector>

#include "ladarsim/sensor_model/signal/counter_random.h"
#include "ladarsim/sensor_model/signal/volume_echoes.h"

namespace ladarsim::sensor_model {

Integration StratifiedSubRays::integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const {
    const Footprint& footprint = context_.shape.footprint();
    thread_local std::vector<SubRay> sub_rays;
    thread_local std::vector<double> uniforms;
    sub_rays.resize(static_cast<std::size_t>(cells_.samples()));
    if (!context_.settings.jitter) {
        cells_.fixed(sub_rays);
    } else {
        // Two cells per block of four draws.
        uniforms.resize(2 * sub_rays.size());
        RandomSequence draws(context_.settings.seed, RandomStream::footprint_jitter, beam.frame, beam.aim.cell, part.first_draw);
        for (double& u : uniforms) u = draws.uniform();
        cells_.jittered(sub_rays, uniforms);
    }
    if (part.excluded) {
        // The part accounted elsewhere is dropped; the rest carry its share, as a region's cells do.
        std::erase_if(sub_rays, [&](const SubRay& s) { return footprint.contains(*part.excluded, s.offset_x_rad, s.offset_y_rad); });
        double kept = 0.0;
        for (const SubRay& s : sub_rays) kept += s.weight;
        for (SubRay& s : sub_rays) s.weight *= part.share / kept;
    }
    trace(beam, sub_rays, out, part.first_draw);
    return {Outcome::integrated, part.share};
}

void StratifiedSubRays::trace(const BeamSetting& beam, std::span<const SubRay> sub_rays, BeamEchoes& out,
                              std::uint32_t first_draw) const {
    const Sensor& sensor = context_.sensor;
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    rays.resize(sub_rays.size());
    hits.resize(sub_rays.size());
    for (std::size_t i = 0; i < sub_rays.size(); ++i) rays[i] = context_.ray(beam.aim, sub_rays[i].offset_x_rad, sub_rays[i].offset_y_rad);
    context_.traced.trace(rays, hits);
    out.rays += static_cast<int>(sub_rays.size());

    // As a region's sub-rays draw theirs: 64 a sub-ray from its number on.
    RandomSequence volume_draws(context_.settings.seed, RandomStream::volume_scatter, beam.frame, beam.aim.cell,
                                std::uint64_t{64} * first_draw);
    for (std::size_t i = 0; i < sub_rays.size(); ++i) {
        const double weight = sub_rays[i].weight;
        double fog = 1.0;
        if (beam.media) {
            thread_local std::vector<raytrace::VolumeSegment> volumes;
            context_.traced.volumes_along(rays[i], volumes);
            add_volume_echoes(volumes, hits[i] ? hits[i]->range_m : sensor.receiver.max_range_m,
                              sensor.transmitter.pulse_energy_j() * weight * sensor.optics.optics_efficiency, weight,
                              sensor.optics.aperture_area_m2(), context_.radiometry.receiver(), volume_draws, out.volume, kFreePaths);
            if (hits[i]) fog = std::exp(-2.0 * optical_depth(volumes, hits[i]->range_m));
        }
        if (!hits[i]) continue;
        const raytrace::Hit& h = *hits[i];
        out.surface.push_back({h.range_m, weight, context_.echo_energy_j(weight, h.reflectance, h.cos_incidence, h.range_m, fog), 0.0,
                               h.object_id, rays[i].origin_world + h.range_m * rays[i].direction, h.normal_world, 0});
    }
}

}  // namespace ladarsim::sensor_model
