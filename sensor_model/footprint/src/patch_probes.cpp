#include "patch_probes.h"

namespace ladarsim::sensor_model {

void PatchProbes::gather(const Footprint& footprint, std::span<const Probe> probes, const std::optional<FootprintRect>& excluded) {
    used.clear();
    gauss.clear();
    hits = 0;
    one_object = true;
    object_id = 0;
    normal_sum = point_sum = Eigen::Vector3d::Zero();
    reflectance_sum = g_sum = 0.0;
    for (const Probe& p : probes) {
        if (excluded && footprint.contains(*excluded, p.x_rad, p.y_rad)) continue;
        if (!footprint.within_truncation(p.x_rad, p.y_rad)) continue;  // a sentinel
        used.push_back(&p);
        if (!p.hit->hit) continue;
        const raytrace::Hit& h = *p.hit->hit;
        if (hits++ == 0) object_id = h.object_id;
        one_object = one_object && h.object_id == object_id;
        const double g = p.irradiance;
        gauss.push_back(g);
        normal_sum += g * h.normal_world.cast<double>();
        point_sum += g * p.hit->point_world;
        reflectance_sum += g * h.reflectance;
        g_sum += g;
    }
}

}  // namespace ladarsim::sensor_model
