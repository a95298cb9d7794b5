#include "straight_edge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "sub_ray_seen.h"

namespace ladarsim::sensor_model {

namespace {

constexpr int kEdgeQuadrature = 8;  // sub-rays spreading each side of a straight edge's share
/// A side of a straight edge is taken to lie on one plane where its points leave the plane fitted to
/// them by at most this fraction of their spread in range (RMS), or the pulse's width.
constexpr double kPlaneFit = 0.1;
/// A side whose echo's peak is bounded below this fraction of the threshold is not resolved in range
/// (the bound, truncation's renormalisation aside, is within 2 % of exact).
constexpr double kUndetectable = 0.5;
/// A side's range profile takes slices this much finer than its spread (or as fine as the pulse).
constexpr double kSlicesPerSpread = 24.0;
/// Points on the rim of the footprint, just inside its truncation, where an edge crossing it enters
/// and leaves; and the bisections that place each end.
constexpr int kRim = 12;
constexpr int kBisections = 5;

/// Share of a round Gaussian (per-axis sigma) truncated at radius r on the far side of a chord at
/// distance d >= 0 from its centre, over its whole truncated mass: the integral over t from d to r
/// of the normal density at t times the normal mass of the chord's half-length sqrt(r^2 - t^2),
/// by 32-point Gauss-Legendre quadrature.
double cap_share(double d, double r, double sigma) {
    static const std::array<double, 16> x = {0.0483076656877383, 0.1444719615827965, 0.2392873622521371, 0.3318686022821277,
                                             0.4213512761306353, 0.5068999089322294, 0.5877157572407623, 0.6630442669302152,
                                             0.7321821187402897, 0.7944837959679424, 0.8493676137325700, 0.8963211557660521,
                                             0.9349060759377397, 0.9647622555875064, 0.9856115115452684, 0.9972638618494816};
    static const std::array<double, 16> w = {0.0965400885147278, 0.0956387200792749, 0.0938443990808046, 0.0911738786957639,
                                             0.0876520930044038, 0.0833119242269467, 0.0781938957870703, 0.0723457941088485,
                                             0.0658222227763618, 0.0586840934785355, 0.0509980592623762, 0.0428358980222267,
                                             0.0342738629130214, 0.0253920653092621, 0.0162743947309057, 0.0070186100094701};
    if (d >= r) return 0.0;
    auto phi = [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); };
    auto mass = [](double z) { return std::erf(z / std::numbers::sqrt2); };  // P(|s| < z) of a unit normal
    const double mid = 0.5 * (r + d), half = 0.5 * (r - d);
    double sum = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        for (const double t : {mid - half * x[k], mid + half * x[k]}) sum += w[k] * phi(t / sigma) / sigma * mass(std::sqrt(std::max(0.0, r * r - t * t)) / sigma);
    }
    return sum * half / -std::expm1(-0.5 * r * r / (sigma * sigma));
}

/// Where the fit looked: a rim point, a probe or a quadrature node, and which surface it met.
struct Point {
    Eigen::Vector2d offset;
    Seen seen;
    int side = -1;  ///< which of the two surfaces
};

/// A side's points, irradiance-weighted: how its range spreads, and for a side no node falls on,
/// its energy and the point nearest the axis.
struct SidePoints {
    double weight = 0.0, energy = 0.0, range = 0.0, range2 = 0.0;
    const Point* nearest = nullptr;
    double mean() const { return range / weight; }
    double variance() const { return std::max(0.0, range2 / weight - mean() * mean()); }
};

/// One try of a straight edge on one beam, step by step; each step false where the edge fails.
/// (One per thread, reused: its lists allocate nothing once warm.)
class EdgeFit {
public:
    void start(const StraightEdge& edge, const BeamSetting& beam, BeamEchoes& out);
    /// The rim's points and the probes inside, each on one of two surfaces.
    bool trace_rim();
    /// The rim changes side exactly twice, the edge's two ends: each bisected in angle, and the
    /// chord between them.
    bool find_chord();
    /// Every point on its surface's side of the chord (those within a bisection's step excepted).
    bool points_on_their_sides() const;
    /// The quadrature's nodes, each on its side too.
    bool spread_over_quadrature();
    /// Each surface's share of the beam, spread over its nodes.
    void append_sides();

private:
    Seen seen_of(const std::optional<raytrace::Hit>& hit, const Eigen::Vector3d& direction) const;
    double energy_of(const Seen& s) const;
    void trace_offsets(std::span<const Eigen::Vector2d> offsets);
    int side_of(const Seen& s);
    /// The side's points stretch its echoes beyond its nodes' own spread; `spread` beyond the pulse:
    /// the shape of its echo in range replaces them (appended from `first`).
    void append_side(int side, double share, const SidePoints& m);
    void resolve_in_range(int side, double share, double spread, std::size_t first);

    const StraightEdge* edge_ = nullptr;
    const FootprintContext* context_ = nullptr;
    const BeamSetting* beam_ = nullptr;
    BeamEchoes* out_ = nullptr;
    double gap_ = 0.0, r_max_ = 0.0, rim_ = 0.0;
    std::vector<Point> points_;
    std::vector<raytrace::Ray> rays_;
    std::vector<std::optional<raytrace::Hit>> hits_;
    std::vector<Eigen::Vector2d> offsets_;
    std::vector<Seen> seen_;  ///< of offsets_; never shrunk: no re-construction
    /// Two surfaces (one may be nothing), each represented by its first point.
    std::array<const Seen*, 2> surface_{nullptr, nullptr};
    std::array<Seen, 2> representative_;
    std::array<int, kRim> rim_side_{};
    std::array<double, 2> lo_{}, hi_{};
    std::array<int, 2> lo_side_{};
    Eigen::Vector2d normal_ = Eigen::Vector2d::Zero();
    double distance_ = 0.0, margin_ = 0.0;
    int cap_side_ = 0;
    std::array<double, 2> weight_on_{0.0, 0.0};
    std::array<int, 2> nodes_on_{0, 0};
    std::vector<int> node_side_;
    std::vector<RangeSample> samples_;
};

void EdgeFit::start(const StraightEdge& edge, const BeamSetting& beam, BeamEchoes& out) {
    edge_ = &edge;
    context_ = &edge.context();
    beam_ = &beam;
    out_ = &out;
    gap_ = context_->return_gap_m;
    r_max_ = context_->shape.footprint().max_offset_rad();
    rim_ = 0.999 * r_max_;
    points_.clear();
    surface_ = {nullptr, nullptr};
}

Seen EdgeFit::seen_of(const std::optional<raytrace::Hit>& hit, const Eigen::Vector3d& direction) const {
    Seen seen;
    if (!hit) return seen;
    seen.hit = true;
    seen.reflectance = hit->reflectance;
    seen.cos_incidence = hit->cos_incidence;
    // Its echo (an exponential) only where it is used.
    seen.echo = {hit->range_m, 1.0, -1.0, 0.0, hit->object_id, beam_->aim.origin_world + hit->range_m * direction,
                 hit->normal_world, 0};
    return seen;
}

double EdgeFit::energy_of(const Seen& s) const {
    return s.echo.energy_j >= 0.0 ? s.echo.energy_j : context_->echo_energy_j(1.0, s.reflectance, s.cos_incidence, s.echo.range_m, 1.0);
}

void EdgeFit::trace_offsets(std::span<const Eigen::Vector2d> offsets) {
    rays_.resize(offsets.size());
    hits_.resize(offsets.size());
    for (std::size_t i = 0; i < offsets.size(); ++i) rays_[i] = context_->ray(beam_->aim, offsets[i].x(), offsets[i].y());
    context_->traced.trace(rays_, hits_);
    out_->rays += static_cast<int>(offsets.size());
    if (seen_.size() < offsets.size()) seen_.resize(offsets.size());
    for (std::size_t i = 0; i < offsets.size(); ++i) seen_[i] = seen_of(hits_[i], rays_[i].direction);
}

int EdgeFit::side_of(const Seen& s) {
    for (std::size_t k = 0; k < 2; ++k) {
        if (!surface_[k]) {
            representative_[k] = s;
            surface_[k] = &representative_[k];
            return static_cast<int>(k);
        }
        if (agree(*surface_[k], s, gap_)) return static_cast<int>(k);
    }
    return -1;  // a third: not one edge
}

bool EdgeFit::trace_rim() {
    offsets_.clear();
    for (int k = 0; k < kRim; ++k) {
        const double a = 2.0 * std::numbers::pi * k / kRim;
        offsets_.emplace_back(rim_ * std::cos(a), rim_ * std::sin(a));
    }
    trace_offsets(offsets_);
    for (std::size_t k = 0; k < kRim; ++k) {
        rim_side_[k] = side_of(seen_[k]);
        if (rim_side_[k] < 0) return false;
        points_.push_back({offsets_[k], seen_[k], rim_side_[k]});
    }
    const Footprint& footprint = context_->shape.footprint();
    for (const Probe* p : beam_->witnesses) {
        if (!footprint.within_truncation(p->x_rad, p->y_rad)) continue;
        Point q{{p->x_rad, p->y_rad}, seen_of(p->hit->hit, p->direction_world), -1};
        q.side = side_of(q.seen);
        if (q.side < 0) return false;
        points_.push_back(q);
    }
    return true;
}

bool EdgeFit::find_chord() {
    std::array<int, 2> change{-1, -1};
    int changes = 0;
    for (int k = 0; k < kRim; ++k) {
        if (rim_side_[static_cast<std::size_t>(k)] == rim_side_[static_cast<std::size_t>((k + 1) % kRim)]) continue;
        if (changes == 2) return false;
        change[static_cast<std::size_t>(changes++)] = k;
    }
    if (changes != 2) return false;
    for (std::size_t c = 0; c < 2; ++c) {
        lo_[c] = 2.0 * std::numbers::pi * change[c] / kRim;
        hi_[c] = lo_[c] + 2.0 * std::numbers::pi / kRim;
    }
    lo_side_ = {rim_side_[static_cast<std::size_t>(change[0])], rim_side_[static_cast<std::size_t>(change[1])]};
    for (int step = 0; step < kBisections; ++step) {
        offsets_.clear();
        for (std::size_t c = 0; c < 2; ++c) {
            const double a = 0.5 * (lo_[c] + hi_[c]);
            offsets_.emplace_back(rim_ * std::cos(a), rim_ * std::sin(a));
        }
        trace_offsets(offsets_);
        for (std::size_t c = 0; c < 2; ++c) {
            const int side = side_of(seen_[c]);
            if (side < 0) return false;
            points_.push_back({offsets_[c], seen_[c], side});
            const double a = 0.5 * (lo_[c] + hi_[c]);
            (side == lo_side_[c] ? lo_ : hi_)[c] = a;
        }
    }
    const double a1 = 0.5 * (lo_[0] + hi_[0]), a2 = 0.5 * (lo_[1] + hi_[1]);
    const Eigen::Vector2d p1(rim_ * std::cos(a1), rim_ * std::sin(a1)), p2(rim_ * std::cos(a2), rim_ * std::sin(a2));
    // The chord between them, its normal pointing away from the axis: the cap beyond it.
    normal_ = Eigen::Vector2d(-(p2 - p1).y(), (p2 - p1).x());
    normal_.normalize();
    distance_ = normal_.dot(p1);
    if (distance_ < 0.0) {
        normal_ = -normal_;
        distance_ = -distance_;
    }
    // Which surface lies in the cap: the rim's, just past the first end towards the cap.
    const double a_cap = normal_.dot(Eigen::Vector2d(std::cos(lo_[0]), std::sin(lo_[0]))) >
                                 normal_.dot(Eigen::Vector2d(std::cos(hi_[0]), std::sin(hi_[0])))
                             ? lo_[0] : hi_[0];
    cap_side_ = a_cap == lo_[0] ? lo_side_[0] : 1 - lo_side_[0];
    margin_ = 2.0 * rim_ * 2.0 * std::numbers::pi / kRim / (1 << kBisections) + 1e-3 * r_max_;
    return true;
}

bool EdgeFit::points_on_their_sides() const {
    // Else the edge is not straight, or there is more than one.
    for (const Point& q : points_) {
        const double along = normal_.dot(q.offset) - distance_;
        if (std::abs(along) < margin_) continue;
        if ((along > 0.0) != (q.side == cap_side_)) return false;
    }
    return true;
}

bool EdgeFit::spread_over_quadrature() {
    offsets_.assign(edge_->quadrature().begin(), edge_->quadrature().end());
    trace_offsets(offsets_);
    weight_on_ = {0.0, 0.0};
    nodes_on_ = {0, 0};
    node_side_.assign(offsets_.size(), -1);
    for (std::size_t k = 0; k < offsets_.size(); ++k) {
        const double along = normal_.dot(offsets_[k]) - distance_;
        const int side = side_of(seen_[k]);
        if (side < 0) return false;
        if (std::abs(along) >= margin_ && (along > 0.0) != (side == cap_side_)) return false;
        node_side_[k] = side;  // by what it met: within the margin, the chord may pass either way
        weight_on_[static_cast<std::size_t>(side)] += 1.0;
        ++nodes_on_[static_cast<std::size_t>(side)];
    }
    return true;
}

void EdgeFit::append_sides() {
    // Each surface takes its share of the beam (exact for a straight edge), spread over the
    // equal-energy nodes on its side, each of which must find that surface; a sliver holding none
    // takes the mean of its points, weighted by the beam's irradiance. A side that few nodes fall
    // on (a grazing sliver spanning tens of metres of range) would otherwise be as compact an echo
    // as its nodes, and be detected where the whole footprint's stretched pulse is not.
    const double cap = cap_share(distance_, r_max_, 0.5 * context_->shape.footprint().waist_rad());
    std::array<SidePoints, 2> side_points;
    for (const Point& q : points_) {
        if (!q.seen.hit) continue;
        SidePoints& m = side_points[static_cast<std::size_t>(q.side)];
        const double g = context_->shape.irradiance(q.offset.x(), q.offset.y());
        m.weight += g;
        m.range += g * q.seen.echo.range_m;
        m.range2 += g * q.seen.echo.range_m * q.seen.echo.range_m;
        if (nodes_on_[static_cast<std::size_t>(q.side)] == 0) m.energy += g * energy_of(q.seen);
        if (!m.nearest || q.offset.squaredNorm() < m.nearest->offset.squaredNorm()) m.nearest = &q;
    }
    for (int side = 0; side < 2; ++side) {
        if (!surface_[static_cast<std::size_t>(side)]->hit) continue;
        append_side(side, side == cap_side_ ? cap : 1.0 - cap, side_points[static_cast<std::size_t>(side)]);
    }
}

void EdgeFit::append_side(int side, double share, const SidePoints& m) {
    const auto s = static_cast<std::size_t>(side);
    const std::size_t first = out_->surface.size();
    const double spread = m.weight > 0.0 ? std::sqrt(m.variance()) : 0.0;
    if (nodes_on_[s] == 0) {
        // A sliver no node falls on takes the mean of its points.
        SurfaceEcho e = m.nearest->seen.echo;
        e.range_m = m.mean();
        e.weight = share;
        e.energy_j = share * m.energy / m.weight;
        e.sample = 0;
        e.spread_m = spread;
        out_->surface.push_back(e);
        if (spread > context_->pulse_sigma_m) resolve_in_range(side, share, spread, first);
        return;
    }
    // The variance of range the side's points show beyond its nodes' own: each node's echo is
    // stretched by it (variances add).
    double node_weight = 0.0, node_mean = 0.0, node_square = 0.0;
    for (std::size_t k = 0; k < offsets_.size(); ++k) {
        if (node_side_[k] != side || !seen_[k].hit) continue;
        node_weight += 1.0;
        node_mean += seen_[k].echo.range_m;
        node_square += seen_[k].echo.range_m * seen_[k].echo.range_m;
    }
    const double missing_variance =
        m.weight > 0.0 && node_weight > 0.0
            ? std::max(0.0, m.variance() - (node_square / node_weight - std::pow(node_mean / node_weight, 2)))
            : 0.0;
    for (std::size_t k = 0; k < offsets_.size(); ++k) {
        if (node_side_[k] != side || !seen_[k].hit) continue;
        SurfaceEcho e = seen_[k].echo;
        e.weight = share / weight_on_[s];
        e.energy_j = energy_of(seen_[k]) * e.weight;
        e.sample = 0;
        e.spread_m = std::sqrt(e.spread_m * e.spread_m + missing_variance);
        out_->surface.push_back(e);
    }
    if (spread > context_->pulse_sigma_m) resolve_in_range(side, share, spread, first);
}

void EdgeFit::resolve_in_range(int side, double share, double spread, std::size_t first) {
    samples_.clear();
    for (const Point& q : points_)
        if (q.side == side && q.seen.hit) samples_.push_back({q.offset, q.seen.echo.range_m});
    for (std::size_t k = 0; k < offsets_.size(); ++k)
        if (node_side_[k] == side && seen_[k].hit) samples_.push_back({offsets_[k], seen_[k].echo.range_m});
    edge_->profile_in_range(beam_->aim, samples_, {normal_, distance_, side == cap_side_}, share, spread, first, *out_);
}

}  // namespace

StraightEdge::StraightEdge(const FootprintContext& context) : context_(context) {
    std::vector<SubRay> nodes(kEdgeQuadrature);
    Footprint(context.shape.footprint().waist_rad() * 2.0, kEdgeQuadrature, context.settings.truncation).fixed(nodes);
    for (const SubRay& s : nodes) quadrature_.emplace_back(s.offset_x_rad, s.offset_y_rad);
}

Integration StraightEdge::integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const {
    thread_local EdgeFit fit;
    fit.start(*this, beam, out);
    if (!fit.trace_rim() || !fit.find_chord() || !fit.points_on_their_sides() || !fit.spread_over_quadrature())
        return {Outcome::declined};
    fit.append_sides();
    return {Outcome::integrated, part.share};
}

void StraightEdge::profile_in_range(const BeamAim& aim, std::span<const RangeSample> samples, const ChordSide& side, double share,
                                    double spread_m, std::size_t first, BeamEchoes& out) const {
    const double r_max = context_.shape.footprint().max_offset_rad();
    const std::optional<RangePlane> plane = fit_range_plane(samples, r_max, std::max(context_.pulse_sigma_m, kPlaneFit * spread_m));
    if (!plane) return;
    double energy = 0.0;
    for (std::size_t k = first; k < out.surface.size(); ++k) energy += out.surface[k].energy_j;
    // Fine slices only where the side could reach the threshold on its own. No part of it is
    // denser in range than the whole beam's marginal across the gradient g, 1 / (sqrt(2 pi) sigma)
    // per radian: its echo peaks below the whole footprint's energy on that surface in one pulse
    // times sigma_r / (g sigma); failing that, below its densest slice's energy per metre times
    // sqrt(2 pi) sigma_r. Otherwise (ground grazed over tens of metres) one echo of the profile's
    // mean range and spread.
    const double sigma = 0.5 * context_.shape.footprint().waist_rad();
    const double reach = kUndetectable * context_.threshold_j;
    thread_local std::vector<RangeSlice> slices;
    slices.clear();
    const bool bright = energy / share * context_.pulse_sigma_m / (plane->per_rad.norm() * sigma) >= reach;
    const double depth = bright ? std::max(context_.pulse_sigma_m, spread_m / kSlicesPerSpread) : std::numeric_limits<double>::infinity();
    if (!range_profile(*plane, side, r_max, sigma, depth, slices)) return;
    RangeSlice one{Eigen::Vector2d::Zero(), 0.0, 1.0, 0.0};
    double densest = 0.0;  // share per metre of range
    for (const RangeSlice& slice : slices) {
        one.offset += slice.share * slice.offset;
        one.range_m += slice.share * slice.range_m;
        densest = std::max(densest, slice.share / (std::sqrt(12.0) * slice.spread_m));
    }
    for (const RangeSlice& slice : slices)
        one.spread_m += slice.share * (std::pow(slice.range_m - one.range_m, 2) + slice.spread_m * slice.spread_m);
    one.spread_m = std::sqrt(one.spread_m);
    if (!bright || energy * densest * context_.pulse_sigma_m * std::sqrt(2.0 * std::numbers::pi) < reach) slices.assign(1, one);
    // The slices lie on the plane fitted: its normal, so that they make one surface however far
    // apart (gather_surfaces), as the echoes they replace did.
    auto on_plane = [&](double x, double y) {
        return Eigen::Vector3d((plane->at_axis_m + plane->per_rad.dot(Eigen::Vector2d(x, y))) * context_.shape.in_beam(x, y));
    };
    const double step = 0.1 * r_max;
    const Eigen::Vector3d in_plane_normal = (on_plane(step, 0.0) - on_plane(0.0, 0.0)).cross(on_plane(0.0, step) - on_plane(0.0, 0.0));
    SurfaceEcho like = out.surface[first];
    if (in_plane_normal.norm() > 0.0) like.normal_world = (aim.world_from_beam * in_plane_normal.normalized()).cast<float>();
    like.sample = 0;
    out.surface.resize(first);
    const Eigen::Vector3d& origin = aim.origin_world;
    for (const RangeSlice& slice : slices) {
        SurfaceEcho e = like;
        e.range_m = slice.range_m;
        e.weight = share * slice.share;
        e.energy_j = energy * slice.share;
        e.spread_m = slice.spread_m;
        // (Along (1, x, y) unnormalised: a footprint's offsets are milliradians, so the point is
        // off by the range times their square, well inside what gather_surfaces allows.)
        e.point_world = origin + slice.range_m * (aim.world_from_beam * Eigen::Vector3d(1.0, slice.offset.x(), slice.offset.y() * context_.shape.ellipticity()));
        out.surface.push_back(e);
    }
}

}  // namespace ladarsim::sensor_model
