#include "ladarsim/sensor_model/signal/volume_echoes.h"

#include "ladarsim/sensor_model/signal/range_equation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ladarsim::sensor_model {

double optical_depth(std::span<const raytrace::VolumeSegment> segments, double range_m) {
    double tau = 0.0;
    for (const auto& s : segments) {
        const double length = std::min(s.exit_m, range_m) - s.enter_m;
        if (length > 0.0) tau += s.extinction_per_m * length;
    }
    return tau;
}

void add_volume_echoes(std::span<const raytrace::VolumeSegment> segments, double surface_range_m,
                       double subray_energy_j, double sub_ray_weight, double aperture_area_m2,
                       const BeamReceiver& receiver, RandomSequence& draws, std::vector<BeamSurface>& volumes,
                       int free_paths) {
    const double r2 = aperture_radius2_m2(aperture_area_m2);
    for (const auto& s : segments) {
        // Scattering closer than the receiver's minimum range is never seen (the medium there still
        // dims what lies beyond): the depths are taken past it, so that an echo made of several
        // is not dragged inside it by the near ones' 1 / R^2.
        const double enter_m = std::max(s.enter_m, receiver.min_range_m());
        const double depth = std::min(s.exit_m, surface_range_m) - enter_m;
        if (!(depth > 0.0) || s.backscatter_per_m_sr <= 0.0) continue;
        const double alpha = s.extinction_per_m;
        const double escape = -std::expm1(-alpha * depth);  // 1 - exp(-alpha d), exact for thin slabs
        // Backscatter per steradian into the solid angle the aperture subtends from the scatterers,
        // pi r_a^2 / (R^2 + r_a^2): pi times the view factor.
        const double t0 = receiver.transmission(enter_m);
        const double scale = subray_energy_j * t0 * t0 * std::exp(-2.0 * optical_depth(segments, enter_m)) * s.backscatter_per_m_sr /
                             alpha * escape * std::numbers::pi / free_paths;
        // Past the entry the clear air's two-way loss and the medium's own, exp(-(2 k + alpha) s), in one.
        const double decay = 2.0 * receiver.extinction_per_m() + alpha;
        // Moments about the segment's entry: the depths are metres, the ranges kilometres.
        double energy = 0.0, moment = 0.0, second = 0.0;
        // Stratified: one draw places all n free paths, one in each n-th of the segment's
        // scattering probability (an estimate far less scattered than n independent draws).
        const double u = draws.uniform();
        for (int k = 0; k < free_paths; ++k) {
            const double free_path = -std::log1p(-(k + u) / free_paths * escape) / alpha;
            const double range = std::max(enter_m + free_path, 1e-3);
            const double e = through_aperture(scale * std::exp(-decay * free_path), r2, range);
            const double d = range - enter_m;
            energy += e;
            moment += e * d;
            second += e * d * d;
        }
        if (!(energy > 0.0)) continue;
        const double mean = moment / energy;
        auto it = std::find_if(volumes.begin(), volumes.end(), [&](const BeamSurface& v) { return v.object_id == s.object_id; });
        if (it == volumes.end()) {
            BeamSurface v;
            v.object_id = s.object_id;
            v.source = ReturnSource::volume;
            volumes.push_back(std::move(v));
            it = volumes.end() - 1;
        }
        it->weight += sub_ray_weight;
        it->echoes.push_back({enter_m + mean, energy, 0, std::sqrt(std::max(0.0, second / energy - mean * mean))});
    }
}

}  // namespace ladarsim::sensor_model
