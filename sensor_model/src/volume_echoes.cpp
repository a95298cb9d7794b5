#include "ladarsim/sensor_model/volume_echoes.h"

#include "ladarsim/sensor_model/range_equation.h"

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
                       const BeamReceiver& receiver, RandomSequence& draws, std::vector<BeamSurface>& volumes) {
    const double r2 = aperture_radius2_m2(aperture_area_m2);
    for (const auto& s : segments) {
        const double depth = std::min(s.exit_m, surface_range_m) - s.enter_m;
        if (!(depth > 0.0) || s.backscatter_per_m_sr <= 0.0) continue;
        const double alpha = s.extinction_per_m;
        const double escape = -std::expm1(-alpha * depth);  // 1 - exp(-alpha d), exact for thin slabs
        const double free_path = -std::log1p(-draws.uniform() * escape) / alpha;
        const double range = std::max(s.enter_m + free_path, 1e-3);
        const double t = receiver.transmission(range);
        // Backscatter per steradian into the solid angle the aperture subtends from the scatterers,
        // pi r_a^2 / (R^2 + r_a^2): pi times the view factor.
        const double energy = through_aperture(subray_energy_j * t * t * std::exp(-2.0 * optical_depth(segments, s.enter_m)) *
                                                   s.backscatter_per_m_sr / alpha * escape * std::exp(-alpha * free_path) *
                                                   std::numbers::pi,
                                               r2, range);
        auto it = std::find_if(volumes.begin(), volumes.end(), [&](const BeamSurface& v) { return v.object_id == s.object_id; });
        if (it == volumes.end()) {
            BeamSurface v;
            v.object_id = s.object_id;
            v.source = ReturnSource::volume;
            volumes.push_back(std::move(v));
            it = volumes.end() - 1;
        }
        it->weight += sub_ray_weight;
        it->echoes.push_back({range, energy, 0});
    }
}

}  // namespace ladarsim::sensor_model
