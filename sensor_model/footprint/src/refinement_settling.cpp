#include "refinement_settling.h"

#include <algorithm>
#include <cmath>

#include "ladarsim/sensor_model/sensor/physical_constants.h"

namespace ladarsim::sensor_model {

namespace {

/// The error bound a refinement stops at, in standard deviations of its estimate.
constexpr double kConfidenceSigmas = 3.0;
constexpr double kAcross = 1e-9;  // a step across a cell's side: far below the finest cell

}  // namespace

bool SettlingPass::settled(const FootprintContext& context, RefinementRegion& r, std::span<const Probe* const> witnesses,
                           std::vector<SurfaceEcho>& echoes, const std::vector<BeamSurface>& volumes) {
    context_ = &context;
    volumes_ = &volumes;
    gap_ = context.return_gap_m;
    group_returns(echoes);
    weigh_returns();
    mark_leaves(r, echoes);
    compare_neighbours(r);
    compare_witnesses(r, witnesses, echoes);
    return decide(r);
}

void SettlingPass::group_returns(std::vector<SurfaceEcho>& echoes) {
    gather_surfaces(echoes, gap_, surfaces_, &surface_of_echo_);
    const double resolution = 0.5 * kSpeedOfLight_mps * context_->sensor.transmitter.pulse_width_ns * 1e-9;
    extent_.resize(surfaces_.size());
    order_.resize(surfaces_.size());
    for (std::size_t g = 0; g < surfaces_.size(); ++g) {
        double lo = surfaces_[g].echoes.front().range_m, hi = lo;
        for (const Echo& e : surfaces_[g].echoes) {
            lo = std::min(lo, e.range_m - e.spread_m);
            hi = std::max(hi, e.range_m + e.spread_m);
        }
        extent_[g] = {lo, hi};
        order_[g] = static_cast<std::uint32_t>(g);
    }
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) { return extent_[a].first < extent_[b].first; });
    merged_.assign(surfaces_.size(), 0);
    clusters_ = 0;
    double reach = -1e300;
    for (const std::uint32_t g : order_) {
        if (clusters_ == 0 || extent_[g].first - reach > resolution) {
            ++clusters_;
            reach = extent_[g].second;
        }
        reach = std::max(reach, extent_[g].second);
        merged_[g] = static_cast<std::uint32_t>(clusters_ - 1);
    }
    for (std::uint32_t& g : surface_of_echo_) g = merged_[g];
    returns_ = clusters_ + volumes_->size();
}

template <class F> void SettlingPass::each_echo(F&& f) const {
    for (const std::uint32_t g : order_)
        for (const Echo& x : surfaces_[g].echoes) f(merged_[g], x);
    for (std::size_t g = 0; g < volumes_->size(); ++g)
        for (const Echo& x : (*volumes_)[g].echoes) f(clusters_ + g, x);
}

void SettlingPass::weigh_returns() {
    energy_.assign(returns_, 0.0);
    variance_.assign(returns_, 0.0);
    threshold_.assign(returns_, 0.0);
    mean_.assign(returns_, 0.0);
    each_echo([&](std::size_t g, const Echo& x) {
        energy_[g] += x.energy_j;
        mean_[g] += x.energy_j * x.range_m;
    });
    spread_.assign(returns_, 0.0);
    for (std::size_t g = 0; g < returns_; ++g)
        if (energy_[g] > 0.0) mean_[g] /= energy_[g];
    each_echo([&](std::size_t g, const Echo& x) {
        if (energy_[g] > 0.0) spread_[g] += x.energy_j * ((x.range_m - mean_[g]) * (x.range_m - mean_[g]) + x.spread_m * x.spread_m);
    });
    for (std::size_t g = 0; g < returns_; ++g)
        threshold_[g] = context_->radiometry.threshold_energy_j(energy_[g] > 0.0 ? std::sqrt(spread_[g] / energy_[g]) : 0.0);
}

void SettlingPass::mark_leaves(RefinementRegion& r, const std::vector<SurfaceEcho>& echoes) {
    for (RefinementRegion::Node& n : r.nodes) {
        n.boundary = n.urgent = false;
        n.want = 0;
        n.adopt = -1;
        n.touches = {-1, -1, -1, -1};
        n.surface = -1;
    }
    for (std::size_t k = 0; k < echoes.size(); ++k) {
        const std::int64_t node = node_of_key(echoes[k].sample);
        if (node >= 0) r.nodes[static_cast<std::size_t>(node)].surface = static_cast<std::int32_t>(surface_of_echo_[k]);
    }
}

std::int32_t SettlingPass::volume_return(std::uint32_t object_id) const {
    for (std::size_t g = 0; g < volumes_->size(); ++g)
        if ((*volumes_)[g].object_id == object_id) return static_cast<std::int32_t>(clusters_ + g);
    return -1;
}

void SettlingPass::add_uncertainty(RefinementRegion::Node& n, std::int32_t g, double energy_j) {
    // Adds (w e / 2)^2 to the variance of the return involved.
    if (g < 0 || !(energy_j > 0.0)) return;
    variance_[static_cast<std::size_t>(g)] += 0.25 * energy_j * energy_j;
    n.boundary = true;
    for (std::int32_t& t : n.touches) {
        if (t == g) break;
        if (t < 0) {
            t = g;
            break;
        }
    }
}

void SettlingPass::involve(const RefinementRegion& r, RefinementRegion::Node& a, const Seen& other, std::int32_t other_surface,
                           std::uint32_t other_volume_first, std::uint32_t other_volume_count) {
    const double w = a.weight * r.scale;
    // Its cell may hold the other's surface (and the other's cell its own: counted from there).
    if (a.surface >= 0) add_uncertainty(a, a.surface, w * a.seen.echo.energy_j);
    if (other.hit) add_uncertainty(a, other_surface, w * other.echo.energy_j);
    for (std::uint32_t v = a.volume_first; v < a.volume_first + a.volume_count; ++v)
        add_uncertainty(a, volume_return(r.volume_echoes[v].object_id), w * r.volume_echoes[v].energy_j);
    for (std::uint32_t v = other_volume_first; v < other_volume_first + other_volume_count; ++v)
        add_uncertainty(a, volume_return(r.volume_echoes[v].object_id), w * r.volume_echoes[v].energy_j);
}

void SettlingPass::compare_neighbours(RefinementRegion& r) {
    for (std::size_t k = 0; k < r.nodes.size(); ++k) {
        if (!r.nodes[k].leaf() || !r.nodes[k].kept) continue;
        for (int side = 0; side < 4; ++side) {
            RefinementRegion::Node& n = r.nodes[k];
            const bool across_x = side < 2;  // right, left: neighbours along x
            const double um = 0.5 * (n.u0 + n.u1), vm = 0.5 * (n.v0 + n.v1);
            const RefinementRegion::Node* m = side == 0   ? r.leaf_at(n.u1 + kAcross, vm)
                                              : side == 1 ? r.leaf_at(n.u0 - kAcross, vm)
                                              : side == 2 ? r.leaf_at(um, n.v1 + kAcross)
                                                          : r.leaf_at(um, n.v0 - kAcross);
            if (!m && r.outline && n.seen.hit) {
                // On an object's outline: what lies beyond is not the object.
                involve(r, n, Seen{}, -1, 0, 0);
                n.want |= across_x ? 1 : 2;
                continue;
            }
            if (!m || !m->kept) continue;
            // Each pair once, from the side of the shorter edge (a finer neighbour compares itself).
            const double n_side = across_x ? n.v1 - n.v0 : n.u1 - n.u0;
            const double m_side = across_x ? m->v1 - m->v0 : m->u1 - m->u0;
            if (m_side < n_side || (m_side == n_side && (side == 1 || side == 3))) continue;
            if (agree(n.seen, m->seen, gap_)) continue;
            RefinementRegion::Node& other = r.nodes[static_cast<std::size_t>(m - r.nodes.data())];
            const std::uint8_t across = across_x ? 1 : 2, along = across_x ? 2 : 1;
            if (n.surface >= 0 && n.surface == other.surface && n.seen.volumes == other.seen.volumes) {
                // Two surfaces within one return (discs of a map, leaves and ground at one
                // range): only their echoes' difference moves its energy.
                const double de = std::abs(n.seen.echo.energy_j - other.seen.echo.energy_j);
                add_uncertainty(n, n.surface, n.weight * r.scale * de);
                add_uncertainty(other, n.surface, other.weight * r.scale * de);
                if (n.boundary) n.want |= across;
                if (other.boundary) other.want |= across;
                continue;
            }
            involve(r, n, other.seen, other.surface, other.volume_first, other.volume_count);
            involve(r, other, n.seen, n.surface, n.volume_first, n.volume_count);
            // Both split across the edge between them; the one coarser along it, along it too.
            n.want |= across;
            other.want |= across;
            if (m_side > n_side) other.want |= along;
        }
    }
}

namespace {

/// Where each witness lies in the region's CDF square and what it met, once per region.
void place_witnesses(const Footprint& footprint, RefinementRegion& r, std::span<const Probe* const> witnesses) {
    r.witness_u.resize(witnesses.size());
    r.witness_v.resize(witnesses.size());
    r.witness_seen.resize(witnesses.size());
    for (std::size_t q = 0; q < witnesses.size(); ++q) {
        const Probe* o = witnesses[q];
        if (!footprint.within_truncation(o->x_rad, o->y_rad)) continue;  // never looked at
        r.witness_u[q] = (footprint.axis_cdf(o->x_rad) - r.cdf_x0) / r.cdf_dx;
        r.witness_v[q] = (footprint.axis_cdf(o->y_rad) - r.cdf_y0) / r.cdf_dy;
        Seen& seen = r.witness_seen[q];
        seen = Seen{};
        if (!o->hit->hit) continue;
        const raytrace::Hit& h = *o->hit->hit;
        seen.hit = true;
        seen.reflectance = h.reflectance;
        // Its echo (an exponential) only when it disagrees (compare_witnesses).
        seen.echo = {h.range_m, 1.0, -1.0, 0.0, h.object_id, o->hit->point_world, h.normal_world, 0};
    }
}

}  // namespace

void SettlingPass::compare_witnesses(RefinementRegion& r, std::span<const Probe* const> witnesses,
                                     const std::vector<SurfaceEcho>& echoes) {
    const Footprint& footprint = context_->shape.footprint();
    for (std::size_t w = 0; w < witnesses.size(); ++w) {
        const Probe* p = witnesses[w];
        if (r.excluded && footprint.contains(*r.excluded, p->x_rad, p->y_rad)) continue;
        if (!footprint.within_truncation(p->x_rad, p->y_rad)) continue;
        if (r.witness_u.size() != witnesses.size()) place_witnesses(footprint, r, witnesses);
        const double pu = r.witness_u[w], pv = r.witness_v[w];
        const RefinementRegion::Node* leaf = r.leaf_at(pu, pv);
        if (!leaf || !leaf->kept) continue;
        r.witness_seen[w].volumes = leaf->seen.volumes;  // probes do not look into media
        if (agree(leaf->seen, r.witness_seen[w], gap_)) continue;
        if (r.witness_seen[w].hit && r.witness_seen[w].echo.energy_j < 0.0) {
            const raytrace::Hit& h = *p->hit->hit;
            r.witness_seen[w].echo.energy_j = context_->echo_energy_j(1.0, h.reflectance, h.cos_incidence, h.range_m, 1.0);
        }
        const Seen& probe = r.witness_seen[w];
        RefinementRegion::Node& n = r.nodes[static_cast<std::size_t>(leaf - r.nodes.data())];
        // The probe's surface, if some sub-ray found it; else a return not seen yet.
        std::int32_t probe_surface = -1;
        if (probe.hit) {
            for (std::size_t e = 0; e < echoes.size() && probe_surface < 0; ++e)
                if (echoes[e].object_id == probe.echo.object_id) probe_surface = static_cast<std::int32_t>(surface_of_echo_[e]);
        }
        involve(r, n, probe, probe_surface, 0, 0);
        // Split along the axis the probe lies off the cell's sub-ray (both when alike).
        const double du = std::abs(pu - n.u) / (n.u1 - n.u0), dv = std::abs(pv - n.v) / (n.v1 - n.v0);
        n.want |= static_cast<std::uint8_t>((du >= 0.5 * dv ? 1 : 0) | (dv >= 0.5 * du ? 2 : 0));
        if (!r.media && n.adopt < 0) {
            n.adopt = static_cast<std::int32_t>(r.probes.size());
            r.probes.push_back({pu, pv, probe});
        }
        // Unseen: settled only if even a whole cell of it could not be detected.
        if (probe.hit && probe_surface < 0 &&
            kConfidenceSigmas * 0.5 * n.weight * r.scale * probe.echo.energy_j > context_->settings.tolerance * context_->threshold_j)
            n.urgent = true;
    }
}

bool SettlingPass::decide(RefinementRegion& r) {
    const double tolerance = context_->settings.tolerance;
    unsettled_.assign(returns_, 0);
    for (std::size_t g = 0; g < returns_; ++g)
        unsettled_[g] = kConfidenceSigmas * std::sqrt(variance_[g]) > tolerance * std::max(energy_[g], threshold_[g]);
    // Whether a return is detected at all depends on its pulse's peak, so on how its energy spreads
    // in range, which its sub-rays sample: with n of them the spread (and so the threshold) is known
    // to about 1 / sqrt(n). A return that close to its threshold is undecided: all its cells split.
    undecided_.assign(returns_, 0);
    samples_of_.assign(returns_, 0);
    for (const RefinementRegion::Node& n : r.nodes)
        if (n.leaf() && n.surface >= 0) ++samples_of_[static_cast<std::size_t>(n.surface)];
    for (std::size_t g = 0; g < clusters_; ++g) {
        if (samples_of_[g] == 0) continue;
        const double margin = 1.5 / std::sqrt(2.0 * samples_of_[g]);
        undecided_[g] = std::abs(energy_[g] - threshold_[g]) < margin * threshold_[g];
    }
    if (r.nodes.size() + 4 > r.max_samples) return true;
    bool refinable = false;
    for (RefinementRegion::Node& n : r.nodes) {
        if (!n.leaf()) continue;
        for (const std::int32_t t : n.touches)
            if (t >= 0 && unsettled_[static_cast<std::size_t>(t)]) n.urgent = true;
        if (n.surface >= 0 && undecided_[static_cast<std::size_t>(n.surface)]) {
            n.urgent = true;
            n.want |= 3;
        }
        const std::uint8_t axes = n.want & ((n.splits_x < kMaxSplits ? 1 : 0) | (n.splits_y < kMaxSplits ? 2 : 0));
        refinable = refinable || (n.urgent && axes != 0);
    }
    return !refinable;
}

}  // namespace ladarsim::sensor_model
