#include "ladarsim/sensor_model/footprint_integrator.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ladarsim/sensor_model/counter_random.h"
#include "ladarsim/sensor_model/range_equation.h"
#include "ladarsim/sensor_model/volume_echoes.h"

namespace ladarsim::sensor_model {

namespace {

constexpr double kMradToRad = 1e-3;
constexpr int kFirstLevel = 1;  // 2 x 2 cells, compared with the 4 x 4 of the next level
constexpr int kLastLevel = 5;   // 32 x 32 cells
const double kLevelErrorRatio = std::pow(2.0, 1.5);  // error of a level over that of the next
constexpr int kQuadrature = 16; // directions integrating a plane patch (no rays)
/// Objects subtending less than this many footprint radii can hide between the probes or cover a
/// part of a footprint no probe sees: they are tested against each beam's cone and sampled.
constexpr double kSmallObjectFootprints = 8.0;
/// Where the sampling of the part of the footprint left to the background starts its draws, so
/// that they never repeat those of a target's region in the same beam.
constexpr std::uint32_t kComplementSamples = 1u << 20;

/// How far a continuous surface may bend away from a tangent plane, per metre along it: 5 deg
/// between the facets of a terrain or a hull still make one surface, however far apart the
/// sub-rays that sampled them.
const double kSurfaceBend = std::sin(5.0 * std::numbers::pi / 180.0);

/// Two echoes of one object, neighbours in range, on one continuous surface.
bool same_surface(const SurfaceEcho& a, const SurfaceEcho& b, double gap_m) {
    if (b.range_m - a.range_m <= gap_m) return true;
    const Eigen::Vector3d d = b.point_world - a.point_world;
    const double allowed = gap_m + kSurfaceBend * d.norm();
    return std::abs(a.normal_world.cast<double>().dot(d)) <= allowed && std::abs(b.normal_world.cast<double>().dot(d)) <= allowed;
}

void add_to_tally(std::vector<FootprintIntegrator::Tally>& tally, std::uint32_t object_id, double energy_j) {
    auto it = std::find_if(tally.begin(), tally.end(), [&](const FootprintIntegrator::Tally& t) { return t.object_id == object_id; });
    if (it == tally.end()) tally.push_back({object_id, energy_j});
    else it->energy_j += energy_j;
}

double tallied(const std::vector<FootprintIntegrator::Tally>& tally, std::uint32_t object_id) {
    const auto it = std::find_if(tally.begin(), tally.end(), [&](const FootprintIntegrator::Tally& t) { return t.object_id == object_id; });
    return it == tally.end() ? 0.0 : it->energy_j;
}

}  // namespace

std::vector<BeamSurface> gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m) {
    // One object at a time: a surface is one object's, so that a return always names the object
    // whose echo made it (ground running into a wall's foot stays ground, the wall stays the wall;
    // their pulses still merge in the waveform when they overlap).
    std::sort(echoes.begin(), echoes.end(), [](const SurfaceEcho& a, const SurfaceEcho& b) {
        return a.object_id != b.object_id ? a.object_id < b.object_id : a.range_m < b.range_m;
    });
    std::vector<BeamSurface> surfaces;
    for (std::size_t first = 0; first < echoes.size();) {
        std::size_t last = first + 1;
        while (last < echoes.size() && echoes[last].object_id == echoes[first].object_id &&
               same_surface(echoes[last - 1], echoes[last], gap_m))
            ++last;
        BeamSurface surface;
        surface.object_id = echoes[first].object_id;
        for (std::size_t k = first; k < last; ++k) {
            surface.weight += echoes[k].weight;
            // A sub-ray stands for its cell of the surface, which reaches about half-way to the
            // ranges of its neighbours: its pulse is stretched by that much, so that a sparsely
            // sampled surface draws one continuous echo, not a comb of spurious peaks.
            const double before = k > first ? echoes[k].range_m - echoes[k - 1].range_m : 0.0;
            const double after = k + 1 < last ? echoes[k + 1].range_m - echoes[k].range_m : 0.0;
            const double spread = std::max(echoes[k].spread_m, 0.5 * std::max(before, after));
            surface.echoes.push_back({echoes[k].range_m, echoes[k].energy_j, 0, spread});
        }
        surfaces.push_back(std::move(surface));
        first = last;
    }
    return surfaces;
}

FootprintIntegrator::FootprintIntegrator(const Scenario& scenario, const raytrace::TracedScene& traced,
                                         const BeamReceiver& receiver)
    : scenario_(scenario),
      traced_(traced),
      receiver_(receiver),
      adaptive_(scenario.render.footprint_samples == 0),
      tolerance_(scenario.render.footprint_tolerance),
      floor_energy_j_(receiver.apd().threshold_a() /
                      (receiver.apd().amps_per_watt() * receiver.waveform().pulse().peak_per_joule())),
      ellipticity_(scenario.sensor.transmitter.divergence_el_mrad / scenario.sensor.transmitter.divergence_mrad),
      small_object_rad_(0.0),
      aperture_radius2_(aperture_radius2_m2(scenario.sensor.optics.aperture_area_m2())),
      footprint_(scenario.sensor.transmitter.divergence_mrad * kMradToRad, adaptive_ ? kQuadrature : scenario.render.footprint_samples,
                 scenario.render.footprint_truncation) {
    small_object_rad_ = kSmallObjectFootprints * footprint_.max_offset_rad();
    if (!adaptive_) return;
    std::vector<SubRay> nodes(kQuadrature);
    footprint_.fixed(nodes);
    for (const SubRay& s : nodes) {
        quadrature_in_beam_.push_back(in_beam(s.offset_x_rad, s.offset_y_rad));
        quadrature_x_.push_back(s.offset_x_rad);
        quadrature_y_.push_back(s.offset_y_rad);
    }
}

Eigen::Vector2d FootprintIntegrator::offset_of(const Eigen::Vector3d& v) const {
    return {std::atan2(v.y(), v.x()), std::atan2(v.z(), v.x()) / ellipticity_};
}

Eigen::Vector3d FootprintIntegrator::in_beam(double x_rad, double y_rad) const {
    // tan(a) = a + a^3 / 3 + 2 a^5 / 15 + ...: below 0.01 rad the series' first two terms are exact
    // to 1e-9 relative, and cost a tenth of std::tan (footprints are milliradians).
    auto tangent = [](double a) { return std::abs(a) < 0.01 ? a + a * a * a / 3.0 : std::tan(a); };
    // The footprint is round in units of the azimuth divergence; elliptical beams stretch it in elevation.
    return Eigen::Vector3d(1.0, tangent(x_rad), tangent(y_rad * ellipticity_)).normalized();
}

double FootprintIntegrator::irradiance(double x_rad, double y_rad) const {
    const double w = footprint_.waist_rad();
    return std::exp(-2.0 * (x_rad * x_rad + y_rad * y_rad) / (w * w));
}

double FootprintIntegrator::echo_energy_j(double weight, double reflectance, double cos_incidence, double range_m,
                                          double fog) const {
    const auto& sensor = scenario_.sensor;
    const double t = receiver_.transmission(range_m);
    return lambertian_echo_energy_j(sensor.transmitter.pulse_energy_j(), weight, sensor.optics.optics_efficiency, t * t * fog,
                                    reflectance, cos_incidence, sensor.optics.aperture_area_m2(), range_m);
}

void FootprintIntegrator::integrate(const BeamAim& aim, std::span<const Probe> probes, std::uint64_t frame,
                                    BeamEchoes& out) const {
    out.surface.clear();
    out.volume.clear();
    out.rays = 0;
    if (!adaptive_) {
        thread_local std::vector<SubRay> sub_rays;
        sub_rays.resize(static_cast<std::size_t>(footprint_.samples()));
        const std::span<const double> u = jitter(aim, frame, 0, sub_rays.size());
        if (u.empty()) footprint_.fixed(sub_rays);
        else footprint_.jittered(sub_rays, u);
        trace(aim, sub_rays, traced_.has_volumes(), frame, 0, out, nullptr);
        return;
    }

    // Which objects can this beam's cone touch, at its time?
    thread_local std::vector<raytrace::ObjectBounds> objects;
    traced_.object_bounds(aim.time_s, objects);
    const Eigen::Vector3d& origin = scenario_.mount.position_world;
    const Eigen::Matrix3d beam_from_world = aim.world_from_beam.transpose();
    const double r_max = footprint_.max_offset_rad();
    bool media = false;
    std::optional<FootprintRect> targets;  ///< the outline of every small or moving object met
    for (const raytrace::ObjectBounds& b : objects) {
        const Eigen::Vector3d v = beam_from_world * (b.centre_world - origin);
        const double distance = v.norm();
        const bool inside = distance <= b.radius_m;
        const double angular_radius = inside ? std::numbers::pi / 2.0 : std::asin(b.radius_m / distance);
        if (!b.volume && !b.moving && angular_radius >= small_object_rad_) continue;  // the probes see it
        // Behind the sensor, or beside it: no part of the sphere is within 90 degrees of the axis.
        if (!inside && v.x() <= 0.0) continue;
        if (!inside) {
            // The cone against the sphere (whose disc an elliptical beam's coordinates stretch).
            const Eigen::Vector2d c = offset_of(v);
            if (c.norm() - 1.01 * angular_radius * std::max(1.0, 1.0 / ellipticity_) >= r_max) continue;
        }
        if (b.volume) {
            media = true;
            continue;
        }
        // The outline of the object's box as the beam sees it: its eight corners' offsets.
        FootprintRect outline{r_max, -r_max, r_max, -r_max};
        bool in_front = !inside;
        for (int k = 0; k < 8 && in_front; ++k) {
            const Eigen::Vector3d corner = b.box_model.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
            const Eigen::Vector3d c = beam_from_world * (b.world_from_model * corner.homogeneous() - origin);
            in_front = c.x() > 0.0;
            const Eigen::Vector2d o = offset_of(c);
            outline = {std::min(outline.x_lo, o.x()), std::max(outline.x_hi, o.x()), std::min(outline.y_lo, o.y()),
                       std::max(outline.y_hi, o.y())};
        }
        if (!in_front) {
            outline = {-r_max, r_max, -r_max, r_max};  // straddles the sensor: anywhere
        } else {
            // Padded for Embree's single-precision placement of the mesh, and no more: a cell
            // straddling the outline counts whole when its sub-ray hits, so padding is bias.
            const double pad = 1e-5 * std::max(outline.x_hi - outline.x_lo, outline.y_hi - outline.y_lo) + 1e-9;
            outline = {outline.x_lo - pad, outline.x_hi + pad, outline.y_lo - pad, outline.y_hi + pad};
        }
        const std::optional<FootprintRect> seen = footprint_.clip(outline);
        if (!seen) continue;
        // Several at once (rare): one rectangle around them all.
        targets = targets ? FootprintRect{std::min(targets->x_lo, seen->x_lo), std::max(targets->x_hi, seen->x_hi),
                                          std::min(targets->y_lo, seen->y_lo), std::max(targets->y_hi, seen->y_hi)}
                          : *seen;
    }

    // Targets are sampled where they can be; the rest of the footprint, like a footprint without
    // targets, is one plane patch when the probes agree, and sampled otherwise (always in media).
    const FootprintRegion whole = footprint_.whole();
    if (targets) {
        const double rest = 1.0 - sample(aim, *targets, std::nullopt, 0.0, media, frame, out);
        if (rest > 1e-9 && (media || plane_patch(aim, probes, targets, rest, out) == Patch::mixed))
            sample(aim, whole, targets, rest, media, frame, out);
        return;
    }
    if (media || plane_patch(aim, probes, std::nullopt, 1.0, out) == Patch::mixed)
        sample(aim, whole, std::nullopt, 1.0, media, frame, out);
}

std::span<const double> FootprintIntegrator::jitter(const BeamAim& aim, std::uint64_t frame, std::uint32_t first_sample,
                                                    std::size_t cells) const {
    if (!scenario_.render.jitter) return {};
    thread_local std::vector<double> uniforms;
    uniforms.resize(2 * cells);
    // Two cells per block of four draws: the blocks of `cells` cells starting at `first_sample`
    // end before those of the next `cells` start.
    RandomSequence draws(scenario_.render.seed, RandomStream::footprint_jitter, frame, aim.cell, first_sample);
    for (double& u : uniforms) u = draws.uniform();
    return uniforms;
}

template <class Region>
double FootprintIntegrator::sample(const BeamAim& aim, const Region& region, const std::optional<FootprintRect>& excluded,
                                   double share, bool media, std::uint64_t frame, BeamEchoes& out) const {
    thread_local std::vector<SubRay> grid, kept;
    thread_local std::vector<Tally> tally, previous;
    const std::size_t surface_before = out.surface.size();
    const std::size_t volume_before = out.volume.size();
    std::uint32_t first_sample = excluded ? kComplementSamples : 0;
    previous.clear();
    for (int level = kFirstLevel;; ++level) {
        const int n = 1 << level;
        const std::size_t cells = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
        grid.resize(cells);
        footprint_.grid(region, n, grid, jitter(aim, frame, first_sample, cells));
        kept.clear();
        double kept_weight = 0.0;
        for (const SubRay& sub : grid) {
            if (sub.weight <= 0.0) continue;
            if (excluded && footprint_.contains(*excluded, sub.offset_x_rad, sub.offset_y_rad)) continue;
            kept.push_back(sub);
            kept_weight += sub.weight;
        }
        // With a share given, the kept cells carry it (the excluded part is accounted elsewhere).
        if (share > 0.0 && kept_weight > 0.0) {
            for (SubRay& sub : kept) sub.weight *= share / kept_weight;
            kept_weight = share;
        }
        out.surface.resize(surface_before);
        out.volume.resize(volume_before);
        tally.clear();
        trace(aim, kept, media, frame, first_sample, out, &tally);
        // Converged when this level agrees with the previous one (4 x fewer cells) on every
        // object's energy. Their difference is mostly the coarser level's error; jittered
        // stratification of an edge errs as cells^(-3/4), so this level's error is the difference
        // over 2^(3/2) (errors well below the detection threshold do not count).
        auto agrees = [&](const Tally& t) {
            return std::abs(tallied(tally, t.object_id) - tallied(previous, t.object_id)) <=
                   kLevelErrorRatio * tolerance_ * std::max(tallied(tally, t.object_id), floor_energy_j_);
        };
        const bool converged = level > kFirstLevel && !kept.empty() && std::all_of(tally.begin(), tally.end(), agrees) &&
                               std::all_of(previous.begin(), previous.end(), agrees);
        if (converged || level == kLastLevel) return kept_weight;
        std::swap(tally, previous);
        first_sample += static_cast<std::uint32_t>(cells);
    }
}

void FootprintIntegrator::trace(const BeamAim& aim, std::span<const SubRay> sub_rays, bool media, std::uint64_t frame, std::uint32_t first_sample, BeamEchoes& out,
                                std::vector<Tally>* tally) const {
    const auto& sensor = scenario_.sensor;
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    rays.resize(sub_rays.size());
    hits.resize(sub_rays.size());
    for (std::size_t i = 0; i < sub_rays.size(); ++i) {
        rays[i].origin_world = scenario_.mount.position_world;
        rays[i].direction = aim.world_from_beam * in_beam(sub_rays[i].offset_x_rad, sub_rays[i].offset_y_rad);
        rays[i].time_s = aim.time_s;
        rays[i].max_range_m = sensor.receiver.max_range_m;
    }
    traced_.trace(rays, hits);
    out.rays += static_cast<int>(sub_rays.size());

    // Enough blocks per sub-ray that refinement levels never share volume draws.
    RandomSequence volume_draws(scenario_.render.seed, RandomStream::volume_scatter, frame, aim.cell, 64 * first_sample);
    for (std::size_t i = 0; i < sub_rays.size(); ++i) {
        const double weight = sub_rays[i].weight;
        double fog = 1.0;
        if (media) {
            const std::vector<raytrace::VolumeSegment> volumes = traced_.volumes_along(rays[i]);
            add_volume_echoes(volumes, hits[i] ? hits[i]->range_m : sensor.receiver.max_range_m,
                              sensor.transmitter.pulse_energy_j() * weight * sensor.optics.optics_efficiency, weight,
                              sensor.optics.aperture_area_m2(), receiver_, volume_draws, out.volume);
            if (hits[i]) fog = std::exp(-2.0 * optical_depth(volumes, hits[i]->range_m));
        }
        if (!hits[i]) continue;
        const raytrace::Hit& h = *hits[i];
        const double energy = echo_energy_j(weight, h.reflectance, h.cos_incidence, h.range_m, fog);
        out.surface.push_back({h.range_m, weight, energy, 0.0, h.object_id,
                               rays[i].origin_world + h.range_m * rays[i].direction, h.normal_world});
        if (tally) add_to_tally(*tally, h.object_id, energy);
    }
}

FootprintIntegrator::Patch FootprintIntegrator::plane_patch(const BeamAim& aim, std::span<const Probe> probes,
                                                            const std::optional<FootprintRect>& excluded,
                                                            double weight, BeamEchoes& out) const {
    const Eigen::Vector3d& origin = scenario_.mount.position_world;
    // The probes outside the excluded part speak for the patch, each weighted by the beam's
    // irradiance where it points.
    thread_local std::vector<const Probe*> used;
    thread_local std::vector<double> gauss;
    used.clear();
    gauss.clear();
    int hits = 0;
    bool one_object = true;
    std::uint32_t object_id = 0;
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero(), point_sum = Eigen::Vector3d::Zero();
    double reflectance_sum = 0.0, g_sum = 0.0;
    for (const Probe& p : probes) {
        if (excluded && footprint_.contains(*excluded, p.x_rad, p.y_rad)) continue;
        used.push_back(&p);
        if (!*p.hit) continue;
        const raytrace::Hit& h = **p.hit;
        if (hits++ == 0) object_id = h.object_id;
        one_object = one_object && h.object_id == object_id;
        const double g = p.irradiance;
        gauss.push_back(g);
        normal_sum += g * h.normal_world.cast<double>();
        point_sum += g * (origin + h.range_m * p.direction_world);
        reflectance_sum += g * h.reflectance;
        g_sum += g;
    }
    if (used.empty()) return Patch::mixed;  // nothing to go by
    if (hits == 0) return Patch::empty;
    if (hits < static_cast<int>(used.size()) || !one_object || normal_sum.norm() < 1e-9 * g_sum) return Patch::mixed;
    const Eigen::Vector3d normal = normal_sum.normalized();
    const Eigen::Vector3d centroid = point_sum / g_sum;
    const double reflectance = reflectance_sum / g_sum;
    const double plane_distance = normal.dot(centroid - origin);

    // One plane: every probe within the pulse's resolution of it, and the energy each probe saw
    // consistent with the plane's (the ratio's standard error within the tolerance).
    double q_sum = 0.0, q2_sum = 0.0, g2_sum = 0.0;
    for (std::size_t k = 0; k < used.size(); ++k) {
        const Probe& p = *used[k];
        const raytrace::Hit& h = **p.hit;
        const Eigen::Vector3d point = origin + h.range_m * p.direction_world;
        if (std::abs(normal.dot(point - centroid)) > scenario_.sensor.receiver.return_gap_m) return Patch::mixed;
        const double nd = normal.dot(p.direction_world);
        if (std::abs(nd) < 1e-9) return Patch::mixed;
        const double model_range = plane_distance / nd;
        const double model = reflectance * std::abs(nd) / (model_range * model_range);
        const double seen = h.reflectance * h.cos_incidence / (h.range_m * h.range_m);
        // A black patch (reflectance 0, e.g. a map point recorded with intensity 0) sees nothing
        // and the plane predicts nothing: they agree.
        const double q = model > 0.0 ? seen / model : 1.0;
        q_sum += gauss[k] * q;
        q2_sum += gauss[k] * q * q;
        g2_sum += gauss[k] * gauss[k];
    }
    const double q_mean = q_sum / g_sum;
    const double q_variance = std::max(0.0, q2_sum / g_sum - q_mean * q_mean);
    // Standard error of a weighted mean: sigma sqrt(sum g^2) / sum g.
    if (std::sqrt(q_variance * g2_sum) / g_sum > tolerance_ * q_mean) return Patch::mixed;

    // Integrate the plane over the footprint (outside the excluded part): no rays needed.
    double e_sum = 0.0, et_sum = 0.0, et2_sum = 0.0;
    int nodes = 0;
    for (std::size_t k = 0; k < quadrature_in_beam_.size(); ++k) {
        if (excluded && footprint_.contains(*excluded, quadrature_x_[k], quadrature_y_[k])) continue;
        const Eigen::Vector3d d = aim.world_from_beam * quadrature_in_beam_[k];
        const double nd = normal.dot(d);
        const double range = plane_distance / nd;
        if (!(range > 0.0) || range > scenario_.sensor.receiver.max_range_m) return Patch::mixed;
        // Clear-air transmission is applied below at the patch's mean range: across a footprint
        // it changes by exp(-2 alpha dR), a fraction of a percent even at grazing incidence.
        // The range dependence of through_aperture, relative to the patch's mean range below.
        const double e = std::abs(nd) / (range * range + aperture_radius2_);
        e_sum += e;
        et_sum += e * range;
        et2_sum += e * range * range;
        ++nodes;
    }
    if (nodes == 0) return Patch::mixed;
    const double range = et_sum / e_sum;
    const double spread = std::sqrt(std::max(0.0, et2_sum / e_sum - range * range));
    const double energy = q_mean * echo_energy_j(weight, reflectance, 1.0, range, 1.0) *
                          (range * range + aperture_radius2_) * e_sum / nodes;
    out.surface.push_back({range, weight, energy, spread, object_id, origin + range * aim.world_from_beam.col(0),
                           normal.cast<float>()});
    return Patch::plane;
}

}  // namespace ladarsim::sensor_model
