#include "plane_patch.h"

#include <algorithm>
#include <cmath>

#include "ladarsim/core/units.h"

namespace ladarsim::sensor_model {

PlanePatch::PlanePatch(const FootprintContext& context, const CurvedPatch& curved) : context_(context), curved_(curved) {
    // The equal-energy cells of an adaptive footprint (which has kPlaneQuadrature of them).
    std::vector<SubRay> nodes(kPlaneQuadrature);
    const Footprint quadrature(context.sensor.transmitter.divergence_mrad * kMrad, kPlaneQuadrature, context.settings.truncation);
    quadrature.fixed(nodes);
    within_cells_ = quadrature.variance_over_fixed();
    for (const SubRay& s : nodes) {
        quadrature_in_beam_.push_back(context.shape.in_beam(s.offset_x_rad, s.offset_y_rad));
        quadrature_x_.push_back(s.offset_x_rad);
        quadrature_y_.push_back(s.offset_y_rad);
    }
}

Integration PlanePatch::integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const {
    const Eigen::Vector3d& origin = beam.aim.origin_world;
    const Footprint& footprint = context_.shape.footprint();
    const double weight = part.share;
    // The probes outside the excluded part speak for the patch, each weighted by the beam's
    // irradiance where it points.
    thread_local PatchProbes probes;
    probes.gather(footprint, beam.probes, part.excluded);
    if (probes.used.empty()) return {Outcome::declined};  // nothing to go by
    if (probes.hits == 0) return {Outcome::empty};
    if (probes.hits < static_cast<int>(probes.used.size()) || !probes.one_object) return {Outcome::parted};
    if (probes.normal_sum.norm() < 1e-9 * probes.g_sum) return {Outcome::declined};
    const Eigen::Vector3d normal = probes.normal_sum.normalized();
    const Eigen::Vector3d centroid = probes.point_sum / probes.g_sum;
    const double reflectance = probes.reflectance_sum / probes.g_sum;
    const double plane_distance = normal.dot(centroid - origin);

    // One plane: every probe within the pulse's resolution of it, and the energy each probe saw
    // consistent with the plane's (the ratio's standard error within the tolerance).
    double q_sum = 0.0, q2_sum = 0.0, g2_sum = 0.0;
    const double gap = context_.return_gap_m;
    const double plane_distance2 = plane_distance * plane_distance;
    for (std::size_t k = 0; k < probes.used.size(); ++k) {
        const Probe& p = *probes.used[k];
        const Eigen::Vector3d& point = p.hit->point_world;
        if (std::abs(normal.dot(point - centroid)) > gap) return curved_.integrate(beam, part, probes, out);
        const double nd = normal.dot(p.direction_world);
        if (std::abs(nd) < 1e-9) return {Outcome::declined};
        // What the plane predicts the probe saw: reflectance |nd| / range^2 at the range
        // plane_distance / nd, so reflectance |nd|^3 / plane_distance^2 (one division, not three).
        const double model = reflectance * std::abs(nd) * nd * nd;
        const double seen = p.hit->seen;
        // A black patch (reflectance 0, e.g. a map point recorded with intensity 0) sees nothing
        // and the plane predicts nothing: they agree.
        const double q = model > 0.0 ? seen * plane_distance2 / model : 1.0;
        q_sum += probes.gauss[k] * q;
        q2_sum += probes.gauss[k] * q * q;
        g2_sum += probes.gauss[k] * probes.gauss[k];
    }
    const double q_mean = q_sum / probes.g_sum;
    const double q_variance = std::max(0.0, q2_sum / probes.g_sum - q_mean * q_mean);
    // Standard error of a weighted mean: sigma sqrt(sum g^2) / sum g.
    if (std::sqrt(q_variance * g2_sum) / probes.g_sum > context_.settings.tolerance * q_mean) return {Outcome::declined};

    // Integrate the plane over the footprint (outside the excluded part): no rays needed.
    double e_sum = 0.0, et_sum = 0.0, et2_sum = 0.0;
    int nodes = 0;
    const Eigen::Vector3d normal_in_beam = beam.aim.world_from_beam.transpose() * normal;  // n . (R q) = (R^T n) . q
    for (std::size_t k = 0; k < quadrature_in_beam_.size(); ++k) {
        if (part.excluded && footprint.contains(*part.excluded, quadrature_x_[k], quadrature_y_[k])) continue;
        const double nd = normal_in_beam.dot(quadrature_in_beam_[k]);
        const double range = plane_distance / nd;
        if (!(range > 0.0) || range > context_.max_range_m) return {Outcome::declined};
        // Clear-air transmission is applied below at the patch's mean range: across a footprint
        // it changes by exp(-2 alpha dR), a fraction of a percent even at grazing incidence.
        // The range dependence of through_aperture, relative to the patch's mean range below.
        const double e = std::abs(nd) / (range * range + context_.aperture_radius2);
        e_sum += e;
        et_sum += e * range;
        et2_sum += e * range * range;
        ++nodes;
    }
    if (nodes == 0) return {Outcome::declined};
    const double range = et_sum / e_sum;
    const double spread = std::sqrt(within_cells_ * std::max(0.0, et2_sum / e_sum - range * range));
    const double energy = q_mean * context_.echo_energy_j(weight, reflectance, 1.0, range, 1.0) *
                          (range * range + context_.aperture_radius2) * e_sum / nodes;
    out.surface.push_back({range, weight, energy, spread, probes.object_id, origin + range * beam.aim.world_from_beam.col(0),
                           normal.cast<float>()});
    return {Outcome::integrated, weight};
}


}  // namespace ladarsim::sensor_model
