#include "ladarsim/sensor_model/footprint_integrator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <utility>

#include "ladarsim/sensor_model/counter_random.h"
#include "ladarsim/sensor_model/curved_patch.h"
#include "ladarsim/sensor_model/edge_profile.h"
#include "ladarsim/sensor_model/physical_constants.h"
#include "ladarsim/sensor_model/range_equation.h"
#include "ladarsim/sensor_model/sub_ray_lattice.h"
#include "ladarsim/sensor_model/target_lattice.h"
#include "ladarsim/sensor_model/volume_echoes.h"

namespace ladarsim::sensor_model {

namespace {

constexpr double kMradToRad = 1e-3;
constexpr int kQuadrature = 16; // directions integrating a plane patch (no rays)
constexpr int kEdgeQuadrature = 8;  // sub-rays spreading each side of a straight edge's share
/// Directions integrating a curved patch (no rays). Each takes one facet whole where the facets
/// fold between two lines of probes: with 16 (a plane patch's) a hill's crown grazed at 1 and 2 km
/// came out 6.5 % short in range spread, with 32 2.6 % (64: 1.1 %, the horizon 3 % slower).
constexpr int kCurvedQuadrature = 32;
/// A side of a straight edge is taken to lie on one plane where its points leave the plane fitted to
/// them by at most this fraction of their spread in range (RMS), or the pulse's width.
constexpr double kPlaneFit = 0.1;
/// A side whose echo's peak is bounded below this fraction of the threshold is not resolved in range
/// (the bound, truncation's renormalisation aside, is within 2 % of exact).
constexpr double kUndetectable = 0.5;
/// A side's range profile takes slices this much finer than its spread (or as fine as the pulse).
constexpr double kSlicesPerSpread = 24.0;
/// Objects subtending less than this many footprint radii can hide between the probes or cover a
/// part of a footprint no probe sees: they are tested against each beam's cone and sampled.
constexpr double kSmallObjectFootprints = 8.0;
/// Where the sampling of the part of the footprint left to the background starts its draws, so
/// that they never repeat those of a target's region in the same beam.
constexpr std::uint32_t kComplementSamples = 1u << 23;  // above any region's cell numbers

/// A refined region starts as base x base cells of equal energy (2 x 2 for a whole footprint, whose
/// probes already tell where its edges are; 4 x 4 for a target's outline); a cell splits in two
/// along an axis (or in four), up to 8 times along each (a whole footprint's sliver holding 0.1 %
/// of the beam is resolved), and a region traces at most so many sub-rays.
constexpr int kMaxSplits = 8;
constexpr std::size_t kFootprintSamples = 256;  ///< a whole footprint's (a recorded map's grazing one)
/// A target's outline takes at most 1 / tolerance^2 of these (as a sampled estimate's error falls
/// with its samples), between 256 (tolerance 0.05 and above) and 1024 (0.025 and below); so does
/// a footprint over a recorded map, in stratified cells. A small
/// target of many surfaces within one return (a quadcopter's arms, rotors and body) keeps the
/// estimate's variance above a coarse tolerance through its inner edges: with one cap for every
/// tolerance, each beam near a drone ran to 1024 whatever the tolerance asked.
constexpr double kOutlineSamplesPerInverseTolerance2 = 0.64;
constexpr std::size_t kOutlineSamplesMin = 256, kOutlineSamplesMax = 1024;
constexpr int kFootprintBase = 2;
constexpr int kOutlineBase = 4;
/// Points of a target's surface tried as its seed in each beam that meets it.
constexpr std::size_t kSeedCandidates = 128;
/// Seeds a target takes in each beam: its candidates nearest the axis. Over dataset 2's drone and
/// birds (two frames, noise off, against 4096 sub-rays) a (beam, target) return of the reference's
/// above 5x the threshold was missing 307 times without seeds, 33 with one seed a target, 23 with
/// two, 16 with four, 14 with eight. (Candidates facing the ray only, the edge-on ones dropped,
/// missed more: a bird's wing is a thin box whose edges the reference still sees.)
constexpr std::size_t kSeedsPerTarget = 4;
/// Depths a sub-ray in a medium takes for where it scatters (add_volume_echoes, stratified): they
/// cost no ray, and with one a sub-ray a cloud's return was placed by the few dozen sub-rays of a
/// footprint. The bench's cloud edge, first returns against 4096 sub-rays' (mean / median) and
/// beams/s: 1 depth 167 / 125 mm, 146 k; 4: 42 / 32 mm, 141 k; 8: 21 / 17 mm, 135 k; 16: 11 / 9 mm,
/// 131 k; dataset 3 (a cloud most beams cross) renders in 15.5, 17.7 and 19.8 s at 1, 8 and 16.
constexpr int kFreePaths = 8;
/// A lone target whose echo could reach this many times the threshold (its whole outline's share
/// of the beam, at its brightest material facing the beam, at its nearest range) is sampled by a
/// stratified grid of the outline budget at once instead of refined. Refined, such an outline ran to
/// its budget anyway (89 % of them in the default scenario: a quadcopter's inner edges keep the
/// estimate's variance up), paying a settling pass at every step and spending the budget on the
/// first cells' edges: in the bench's default scenario the grid gives the drone's energy -0.4 %
/// against -1.9 % refined, and such a beam costs half the cycles (115 k against 206-240 k).
/// Several targets together keep refinement: one rectangle around a drone among birds is mostly
/// empty, and the seeds find the drone in it. (Where its line's TargetLattice holds a lone target,
/// bright or dim, the beam takes that instead: this grid is for a footprint whose edge crosses the
/// target, or a raster whose footprints do not overlap along a line.)
constexpr double kBrightTargetThresholds = 3.0;
/// Random-draw numbers of the cells: every (splits along x, splits along y, i, j) its own.
constexpr std::uint32_t cells_along(int base, int splits) { return static_cast<std::uint32_t>(base) << splits; }
constexpr std::uint32_t first_cell_number(int base, int splits_x, int splits_y) {
    std::uint32_t n = 0;
    for (int a = 0; a <= kMaxSplits; ++a)
        for (int b = 0; b <= kMaxSplits; ++b) {
            if (a == splits_x && b == splits_y) return n;
            n += cells_along(base, a) * cells_along(base, b);
        }
    return n;
}
/// The error bound a refinement stops at, in standard deviations of its estimate.
constexpr double kConfidenceSigmas = 3.0;
/// Two sub-rays on one surface whose reflectances differ by more than this factor straddle a change
/// of material (a reflectance edge).
constexpr double kMaterialContrast = 2.0;

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

/// What one sub-ray met, as the refinement compares it with its neighbours'.
struct Seen {
    bool hit = false;
    /// Range, object, point and normal; energy_j per unit of beam share.
    SurfaceEcho echo{0.0, 0.0, 0.0, 0.0, 0, Eigen::Vector3d::Zero(), Eigen::Vector3f::Zero(), 0};
    std::uint64_t volumes = 0;   ///< which media it crossed (one bit per object id modulo 64)
    float reflectance = 0.0f;
    float cos_incidence = 1.0f;
};

/// Whether two sub-rays (or a probe and a sub-ray) can sit in one cell of a smooth integrand: both
/// met nothing, or both met one surface of one object, of reflectances within a factor of each
/// other (the echo itself changes smoothly with range and incidence across a surface).
bool agree(const Seen& a, const Seen& b, double gap_m) {
    if (a.volumes != b.volumes || a.hit != b.hit) return false;
    if (!a.hit) return true;
    if (a.echo.object_id != b.echo.object_id) return false;
    const bool a_first = a.echo.range_m <= b.echo.range_m;
    if (!same_surface(a_first ? a.echo : b.echo, a_first ? b.echo : a.echo, gap_m)) return false;
    const double lo = std::min(a.reflectance, b.reflectance), hi = std::max(a.reflectance, b.reflectance);
    return hi <= kMaterialContrast * lo;
}

/// Indices of `echoes` in order of (object id, range), stable. Most beams bring one or two echoes
/// (an insertion sort: std::stable_sort allocates a buffer on every call); a beam over a recorded
/// map brings hundreds, where a comparison sort's mispredicted branches cost three times a
/// least-significant-digit radix sort on the object id and the range as a float (rounding to float
/// keeps the order, merely making a few near neighbours equal, whose order an insertion pass over
/// the exact ranges then settles: the same order as a stable sort on the exact keys).
void sort_by_object_and_range(const std::vector<SurfaceEcho>& echoes, std::vector<std::uint32_t>& order) {
    const std::size_t n = echoes.size();
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
    auto before = [&](std::uint32_t a, std::uint32_t b) {
        const SurfaceEcho &x = echoes[a], &y = echoes[b];
        return x.object_id != y.object_id ? x.object_id < y.object_id : x.range_m < y.range_m;
    };
    auto insertion = [&] {
        for (std::size_t i = 1; i < n; ++i) {
            const std::uint32_t v = order[i];
            std::size_t j = i;
            for (; j > 0 && before(v, order[j - 1]); --j) order[j] = order[j - 1];
            order[j] = v;
        }
    };
    if (n < 64) {
        insertion();
        return;
    }
    // Eight bytes a key: four of the range as a float (low first), then four of the object id.
    thread_local std::vector<std::array<std::uint32_t, 2>> keys;
    keys.resize(n);
    std::array<std::array<std::uint32_t, 256>, 8> counts{};
    for (std::size_t i = 0; i < n; ++i) {
        // +0 for a negative zero or any negative range (none reaches here), so that bits order.
        const float range = echoes[i].range_m > 0.0 ? static_cast<float>(echoes[i].range_m) : 0.0f;
        std::uint32_t bits;
        std::memcpy(&bits, &range, sizeof bits);
        keys[i] = {bits, echoes[i].object_id};
        for (int b = 0; b < 8; ++b) ++counts[static_cast<std::size_t>(b)][(keys[i][static_cast<std::size_t>(b / 4)] >> (8 * (b % 4))) & 0xFFu];
    }
    thread_local std::vector<std::uint32_t> other;
    other.resize(n);
    for (int b = 0; b < 8; ++b) {
        auto& count = counts[static_cast<std::size_t>(b)];
        const std::size_t word = static_cast<std::size_t>(b / 4);
        const int shift = 8 * (b % 4);
        if (count[(keys[order[0]][word] >> shift) & 0xFFu] == n) continue;  // every key shares this byte
        std::uint32_t start = 0;
        for (std::uint32_t& c : count) {
            const std::uint32_t here = c;
            c = start;
            start += here;
        }
        for (const std::uint32_t i : order) other[count[(keys[i][word] >> shift) & 0xFFu]++] = i;
        order.swap(other);
    }
    insertion();
}

}  // namespace

std::vector<BeamSurface> gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m, std::vector<std::uint32_t>* surface_of_echo) {
    std::vector<BeamSurface> surfaces;
    gather_surfaces(echoes, gap_m, surfaces, surface_of_echo);
    return surfaces;
}

void gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m, std::vector<BeamSurface>& surfaces,
                     std::vector<std::uint32_t>* surface_of_echo) {
    // One object at a time: a surface is one object's, so that a return always names the object
    // whose echo made it (ground running into a wall's foot stays ground, the wall stays the wall;
    // their pulses still merge in the waveform when they overlap). Sorted by (object, range),
    // echoes of equal keys in the order they came, then moved once.
    thread_local std::vector<std::uint32_t> order;
    sort_by_object_and_range(echoes, order);
    thread_local std::vector<SurfaceEcho> sorted;
    sorted.clear();
    for (const std::uint32_t i : order) sorted.push_back(echoes[i]);
    echoes.swap(sorted);
    if (surface_of_echo) surface_of_echo->resize(echoes.size());
    // Echo lists of surfaces dropped from the end, kept for the next beam that needs more.
    thread_local std::vector<std::vector<Echo>> spare;
    std::size_t count = 0;
    for (std::size_t first = 0; first < echoes.size();) {
        std::size_t last = first + 1;
        while (last < echoes.size() && echoes[last].object_id == echoes[first].object_id &&
               same_surface(echoes[last - 1], echoes[last], gap_m))
            ++last;
        if (count == surfaces.size()) {
            surfaces.emplace_back();
            if (!spare.empty()) {
                surfaces.back().echoes = std::move(spare.back());
                spare.pop_back();
            }
        }
        BeamSurface& surface = surfaces[count++];
        surface.echoes.clear();
        surface.weight = 0.0;
        surface.source = ReturnSource::surface;
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
            if (surface_of_echo) (*surface_of_echo)[k] = static_cast<std::uint32_t>(count - 1);
        }
        first = last;
    }
    // (A few: volume surfaces arrive with lists of their own, which would otherwise pile up.)
    for (std::size_t i = count; i < surfaces.size() && spare.size() < 16; ++i) {
        surfaces[i].echoes.clear();
        spare.push_back(std::move(surfaces[i].echoes));
    }
    surfaces.resize(count);
}

/// One rectangle of offsets refined as a tree of cells of equal energy density, in the coordinates
/// of the two axis CDFs (a cell then carries the energy of its area): cells split where their
/// sub-rays disagree with their neighbours', along the axis across which they disagree, so that a
/// straight edge is followed by thin cells along it. A split cell's sub-ray is reused by the child
/// it falls in (with jitter).
struct FootprintIntegrator::Region {
    FootprintRect rect{};
    std::optional<FootprintRect> excluded;  ///< accounted elsewhere: sub-rays there are dropped
    double share = 0.0;                     ///< > 0: the kept cells carry this share of the beam
    std::uint32_t first_sample = 0;         ///< where its random draws start
    double cdf_x0 = 0.0, cdf_dx = 0.0, cdf_y0 = 0.0, cdf_dy = 0.0;

    struct Node {
        double u0, u1, v0, v1;        ///< the cell, in the region's CDF square [0, 1)^2
        std::uint8_t splits_x, splits_y;
        std::uint32_t i, j;           ///< its index along each axis at those splits
        std::int32_t first_child = -1;
        std::uint8_t split = 0;       ///< how it was split: bit 0 along x, bit 1 along y
        std::uint8_t want = 0;        ///< the axes it should split along
        bool traced = false;
        bool kept = true;             ///< not in the excluded part
        bool boundary = false;
        bool urgent = false;          ///< bounds a return whose energy is not settled
        double u, v;                  ///< its sub-ray's place in the CDF square
        double x_rad, y_rad;
        double weight;                ///< the cell's share of the beam (0 beyond the truncation)
        Seen seen;
        std::uint32_t volume_first = 0, volume_count = 0;     ///< its echoes in `volume_echoes`
        std::array<std::int32_t, 4> touches{-1, -1, -1, -1};  ///< returns its cell may hold a part of
        std::int32_t surface = -1;    ///< the return its surface echo went to
        std::int32_t adopt = -1;      ///< a probe inside it that disagrees: in `probes`
        bool leaf() const { return first_child < 0; }
    };
    struct VolumeEcho {
        std::uint32_t object_id;
        double range_m;
        double energy_j;  ///< per unit of beam share
        double spread_m;  ///< of its free paths' ranges
    };
    /// A probe inside the region, as a sub-ray its cell can adopt (no ray needed) once split so
    /// that the probe and the cell's own sub-ray lie apart.
    struct AdoptedProbe {
        double u, v;
        Seen seen;
    };
    std::vector<Node> nodes;  ///< the base cells first, then children, four (or two) together
    std::vector<VolumeEcho> volume_echoes;
    std::vector<AdoptedProbe> probes;
    /// The witnesses' places in the CDF square and what they met, worked out once.
    std::vector<double> witness_u, witness_v;
    std::vector<Seen> witness_seen;
    bool media = false;       ///< sub-rays look into volume media (probes do not: never adopted)
    /// The region is an object's outline: its border is the object's edge somewhere along it, so a
    /// cell on the border whose sub-ray met the object may hold an edge of it.
    bool outline = false;
    int base = kFootprintBase;  ///< cells along each axis to start
    std::size_t max_samples = kFootprintSamples;
    double scale = 1.0;       ///< weights as carried: share / kept weight, or 1

    void reset(const Footprint& footprint, const FootprintRect& r, const std::optional<FootprintRect>& without, double share_of_beam,
               std::uint32_t first) {
        nodes.clear();
        volume_echoes.clear();
        probes.clear();
        witness_u.clear();
        witness_v.clear();
        witness_seen.clear();
        outline = false;
        base = kFootprintBase;
        max_samples = kFootprintSamples;
        rect = r;
        excluded = without;
        share = share_of_beam;
        first_sample = first;
        cdf_x0 = footprint.axis_cdf(r.x_lo);
        cdf_dx = footprint.axis_cdf(r.x_hi) - cdf_x0;
        cdf_y0 = footprint.axis_cdf(r.y_lo);
        cdf_dy = footprint.axis_cdf(r.y_hi) - cdf_y0;
    }
    std::uint32_t number(const Node& n) const {
        return first_sample + first_cell_number(base, n.splits_x, n.splits_y) + n.i * cells_along(base, n.splits_y) + n.j;
    }
    /// Fills a node's sub-ray at (u, v) and its weight.
    void place(const Footprint& footprint, Node& n, double u, double v) const {
        n.u = u;
        n.v = v;
        n.x_rad = footprint.axis_offset(cdf_x0 + u * cdf_dx);
        n.y_rad = footprint.axis_offset(cdf_y0 + v * cdf_dy);
        n.weight = footprint.within_truncation(n.x_rad, n.y_rad)
                       ? footprint.cell_weight(cdf_dx * (n.u1 - n.u0), cdf_dy * (n.v1 - n.v0))
                       : 0.0;
        n.kept = !excluded || !footprint.contains(*excluded, n.x_rad, n.y_rad);
    }
    /// The leaf holding CDF-square point (u, v), or null outside the square.
    const Node* leaf_at(double u, double v) const {
        if (!(u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0)) return nullptr;
        const Node* n = &nodes[static_cast<std::size_t>(std::min(static_cast<int>(u * base), base - 1) * base +
                                                        std::min(static_cast<int>(v * base), base - 1))];
        while (!n->leaf()) {
            const int a = (n->split & 1) && u >= 0.5 * (n->u0 + n->u1) ? 1 : 0;
            const int b = (n->split & 2) && v >= 0.5 * (n->v0 + n->v1) ? 1 : 0;
            n = &nodes[static_cast<std::size_t>(n->first_child + (n->split == 3 ? 2 * a + b : a + b))];
        }
        return n;
    }
};

FootprintIntegrator::FootprintIntegrator(const Scenario& scenario, const raytrace::TracedScene& traced,
                                         const BeamReceiver& receiver)
    : scenario_(scenario),
      traced_(traced),
      receiver_(receiver),
      adaptive_(scenario.render.footprint_samples == 0),
      tolerance_(scenario.render.footprint_tolerance),
      outline_samples_(std::clamp(static_cast<std::size_t>(kOutlineSamplesPerInverseTolerance2 / (tolerance_ * tolerance_)),
                                  kOutlineSamplesMin, kOutlineSamplesMax)),
      ellipticity_(scenario.sensor.transmitter.divergence_el_mrad / scenario.sensor.transmitter.divergence_mrad),
      small_object_rad_(0.0),
      pulse_sigma_m_(PulseShape::of(scenario.sensor.transmitter.pulse_width_ns * 1e-9).sigma_s * 0.5 * kSpeedOfLight_mps),
      grid_base_(static_cast<int>(std::sqrt(static_cast<double>(outline_samples_)))),
      aperture_radius2_(aperture_radius2_m2(scenario.sensor.optics.aperture_area_m2())),
      footprint_(scenario.sensor.transmitter.divergence_mrad * kMradToRad, adaptive_ ? kQuadrature : scenario.render.footprint_samples,
                 scenario.render.footprint_truncation),
      map_cells_(scenario.sensor.transmitter.divergence_mrad * kMradToRad, static_cast<int>(outline_samples_),
                 scenario.render.footprint_truncation) {
    small_object_rad_ = kSmallObjectFootprints * footprint_.max_offset_rad();
    threshold_j_ = threshold_energy_j(0.0);
    if (!adaptive_) return;
    // Seed candidates of each mesh object: centroids of up to kSeedCandidates of its triangles,
    // spread evenly over the mesh's list.
    for (const scene::SceneObject& object : scenario.scene.objects) {
        if (!object.model || object.model->is_volume() || object.model->mesh.triangles.empty()) continue;
        const scene::TriangleMesh& mesh = object.model->mesh;
        const std::size_t stride = (mesh.triangles.size() + kSeedCandidates - 1) / kSeedCandidates;
        TargetShape& shape = target_shapes_[object.id];
        for (std::size_t t = 0; t < mesh.triangles.size(); t += stride) {
            const auto& tri = mesh.triangles[t];
            shape.seed_points.push_back((mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]).cast<double>() / 3.0);
        }
        for (const scene::Material& m : object.model->materials) shape.max_reflectance = std::max(shape.max_reflectance, m.reflectance);
    }
    std::vector<SubRay> nodes(kQuadrature);
    footprint_.fixed(nodes);
    for (const SubRay& s : nodes) {
        quadrature_in_beam_.push_back(in_beam(s.offset_x_rad, s.offset_y_rad));
        quadrature_x_.push_back(s.offset_x_rad);
        quadrature_y_.push_back(s.offset_y_rad);
    }
    std::vector<SubRay> curved_nodes(kCurvedQuadrature);
    Footprint(footprint_.waist_rad() * 2.0, kCurvedQuadrature, scenario.render.footprint_truncation).fixed(curved_nodes);
    for (const SubRay& s : curved_nodes) curved_nodes_.push_back({s.offset_x_rad, s.offset_y_rad, in_beam(s.offset_x_rad, s.offset_y_rad)});
    std::vector<SubRay> edge_nodes(kEdgeQuadrature);
    Footprint(footprint_.waist_rad() * 2.0, kEdgeQuadrature, scenario.render.footprint_truncation).fixed(edge_nodes);
    for (const SubRay& s : edge_nodes) edge_quadrature_.emplace_back(s.offset_x_rad, s.offset_y_rad);
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

double FootprintIntegrator::threshold_energy_j(double spread_m) const {
    const PulseShape shape = PulseShape::of(scenario_.sensor.transmitter.pulse_width_ns * 1e-9, 2.0 * spread_m / kSpeedOfLight_mps);
    const ApdReceiver& apd = receiver_.apd();
    return apd.threshold_a() / (apd.amps_per_watt() * shape.peak_per_joule());
}

void FootprintIntegrator::seed_offsets(const raytrace::ObjectBounds& b, const TargetShape& shape, const Eigen::Matrix3d& beam_from_world,
                                       std::vector<Eigen::Vector2d>& out) const {
    const Eigen::Vector3d& origin = scenario_.mount.position_world;
    // Nearest the axis by the tangents of the offsets (as good as the angles this close to it).
    thread_local std::vector<std::pair<double, Eigen::Vector3d>> candidates;
    candidates.clear();
    for (const Eigen::Vector3d& p : shape.seed_points) {
        const Eigen::Vector3d c = beam_from_world * (b.world_from_model * p.homogeneous() - origin);
        if (!(c.x() > 0.0)) continue;
        const double ty = c.y() / c.x(), tz = c.z() / (c.x() * ellipticity_);
        candidates.emplace_back(ty * ty + tz * tz, c);
    }
    const std::size_t n = std::min(candidates.size(), kSeedsPerTarget);
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(n), candidates.end(),
                      [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d o = offset_of(candidates[k].second);
        if (footprint_.within_truncation(o.x(), o.y())) out.push_back(o);
    }
}

void FootprintIntegrator::integrate(const BeamAim& aim, std::span<const Probe> probes, std::uint64_t frame,
                                    BeamEchoes& out) const {
    out.surface.clear();
    out.volume.clear();
    out.rays = 0;
    if (!adaptive_) {
        stratified(aim, footprint_, traced_.has_volumes(), frame, out, 0, std::nullopt, 1.0);
        return;
    }

    // Which objects can this beam's cone touch, at its time? Only those near its cone are placed
    // and tested below: a cone within r_max of the axis in footprint coordinates stays within
    // max(1, e) r_max of it in angle, and a sphere that passes the test below lies within
    // 1 + 1.01 max(e, 1/e) of its angular radius beyond that (e the ellipticity).
    thread_local std::vector<raytrace::ObjectBounds> objects;
    const double r_max = footprint_.max_offset_rad();
    traced_.object_bounds_near(aim.world_from_beam.col(0), std::max(1.0, ellipticity_) * r_max,
                               1.0 + 1.01 * std::max(ellipticity_, 1.0 / ellipticity_), aim.time_s, small_object_rad_,
                               objects);
    const Eigen::Vector3d& origin = scenario_.mount.position_world;
    const Eigen::Matrix3d beam_from_world = aim.world_from_beam.transpose();
    bool media = false;
    std::optional<FootprintRect> targets;  ///< the outline of every small or moving object met
    int targets_met = 0;
    double brightest_j = 0.0;  ///< the largest echo any of them could send back
    std::uint32_t lone_id = 0;  ///< the last one met: with one, that one
    thread_local std::vector<std::pair<const raytrace::ObjectBounds*, const TargetShape*>> with_seeds;  ///< those with a mesh
    with_seeds.clear();
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
        ++targets_met;
        // Its seeds, and the largest echo it could send back: its outline's share at its brightest
        // material facing the beam at its nearest range (an object without a mesh: reflectance 1).
        double max_reflectance = 1.0;
        const auto shape = target_shapes_.find(b.object_id);
        if (shape != target_shapes_.end()) {
            with_seeds.emplace_back(&b, &shape->second);
            max_reflectance = shape->second.max_reflectance;
        }
        const double share = footprint_.cell_weight(footprint_.axis_cdf(seen->x_hi) - footprint_.axis_cdf(seen->x_lo),
                                                    footprint_.axis_cdf(seen->y_hi) - footprint_.axis_cdf(seen->y_lo));
        brightest_j = std::max(brightest_j, echo_energy_j(share, max_reflectance, 1.0, std::max(distance - b.radius_m, 1e-3), 1.0));
        lone_id = b.object_id;
        // Several at once (a flock, a drone among birds): one rectangle around them all, in which
        // the seeds below keep a sparse one from being missed.
        targets = targets ? FootprintRect{std::min(targets->x_lo, seen->x_lo), std::max(targets->x_hi, seen->x_hi),
                                          std::min(targets->y_lo, seen->y_lo), std::max(targets->y_hi, seen->y_hi)}
                          : *seen;
    }

    // Probes are witnesses of what the sub-rays of their cells must find, unless they met a moving
    // object (a neighbour's probe flew at another time).
    thread_local std::vector<const Probe*> witnesses;
    witnesses.clear();
    for (const Probe& p : probes) {
        const bool moving = p.hit->hit && std::any_of(objects.begin(), objects.end(), [&](const raytrace::ObjectBounds& b) {
            return b.moving && b.object_id == p.hit->hit->object_id;
        });
        if (!moving) witnesses.push_back(&p);
    }
    // Seeds: a ray at a point of each target's surface (where the beam is brightest), at this
    // beam's time, is a witness too: the first cells of an outline are a few sub-rays across a
    // box a thin or sparse target barely fills (a bird's wing edge-on, a quadcopter's arms, a
    // drone in one rectangle with the birds around it), and cells that all meet nothing agree and
    // settle; a seed that met the target splits its cell until it is a cell's sub-ray itself.
    // (Traced only where refinement will ask them: a bright lone target's grid does not.)
    thread_local std::vector<Eigen::Vector2d> seeds_at;
    thread_local std::vector<Probe> seeds;
    thread_local std::vector<ProbeHit> seed_hits;
    thread_local std::vector<raytrace::Ray> seed_rays;
    thread_local std::vector<std::optional<raytrace::Hit>> seed_results;
    bool seeded = false;
    auto add_seeds = [&] {
        if (std::exchange(seeded, true)) return;
        seeds_at.clear();
        for (const auto& [b, shape] : with_seeds) seed_offsets(*b, *shape, beam_from_world, seeds_at);
        if (seeds_at.empty()) return;
        seeds.clear();
        seed_rays.clear();
        for (const Eigen::Vector2d& o : seeds_at) {
            raytrace::Ray ray;
            ray.origin_world = origin;
            ray.direction = aim.world_from_beam * in_beam(o.x(), o.y());
            ray.time_s = aim.time_s;
            ray.max_range_m = scenario_.sensor.receiver.max_range_m;
            seed_rays.push_back(ray);
        }
        seed_results.resize(seed_rays.size());
        traced_.trace(seed_rays, seed_results);
        out.rays += static_cast<int>(seed_rays.size());
        seed_hits.resize(seed_rays.size());  // before any pointer into it is taken
        for (std::size_t k = 0; k < seed_rays.size(); ++k) {
            seed_hits[k].set(seed_results[k], origin, seed_rays[k].direction);
            seeds.push_back({seeds_at[k].x(), seeds_at[k].y(), irradiance(seeds_at[k].x(), seeds_at[k].y()),
                             seed_rays[k].direction, &seed_hits[k]});
        }
        for (const Probe& p : seeds) witnesses.push_back(&p);
    };

    // Targets are sampled where they can be; the rest of the footprint, like a footprint without
    // targets, is one plane patch when the probes agree, and refined otherwise (always in media).
    thread_local Region target_region, rest_region;
    if (targets) {
        const bool bright_lone = targets_met == 1 && brightest_j >= kBrightTargetThresholds * threshold_j_;
        double sampled = 0.0;
        const std::optional<double> shared =
            targets_met == 1 && !media && target_lattice_ ? target_lattice_->gather(aim, lone_id, *targets, out) : std::nullopt;
        if (shared) {
            sampled = *shared;  // its line's sub-rays over it
        } else {
            target_region.reset(footprint_, *targets, std::nullopt, 0.0, 0);
            target_region.outline = true;
            target_region.base = kOutlineBase;
            target_region.max_samples = outline_samples_;
            if (bright_lone) {
                target_region.base = grid_base_;
                target_region.max_samples = static_cast<std::size_t>(grid_base_ * grid_base_);
            } else {
                add_seeds();
            }
            Region* const first[] = {&target_region};
            refine(aim, first, witnesses, media, frame, out);
            for (const Region::Node& n : target_region.nodes)
                if (n.leaf() && n.kept) sampled += n.weight * target_region.scale;
        }
        const double rest = 1.0 - sampled;
        const Patch rest_patch = rest > 1e-9 && !media ? plane_patch(aim, probes, targets, rest, out) : Patch::mixed;
        if (rest > 1e-9 && (rest_patch == Patch::mixed || rest_patch == Patch::parted)) {
            add_seeds();  // (where the target's own sampling did not ask them)
            rest_region.reset(footprint_, footprint_.square(), targets, rest, kComplementSamples);
            Region* const second[] = {&rest_region};
            refine(aim, second, witnesses, media, frame, out, Unsettled::map);
        }
        return;
    }
    if (media) {
        // Probes do not look into media: a cloud's sliver shows only to the sub-rays, 4 x 4 to start.
        rest_region.reset(footprint_, footprint_.square(), std::nullopt, 1.0, 0);
        rest_region.base = kOutlineBase;
        Region* const whole[] = {&rest_region};
        refine(aim, whole, witnesses, media, frame, out, Unsettled::map);
        return;
    }
    const Patch patch = plane_patch(aim, probes, std::nullopt, 1.0, out);
    if (patch == Patch::empty) {
        // Nothing inside; a sentinel that met something: its edge may cross the rim.
        const bool near = std::any_of(probes.begin(), probes.end(), [&](const Probe& p) {
            return p.hit->hit && !footprint_.within_truncation(p.x_rad, p.y_rad);
        });
        if (near) straight_edge(aim, witnesses, out);
        return;
    }
    // Probes parted between something and nothing, or between two objects, are a straight edge
    // (a skyline, a wall against the ground) all but always: over the horizon 17 k such footprints
    // in 60 frames tried one after their first cells and 10 failed; the first cells settled none.
    // So the edge is tried first, and refinement follows only where it fails.
    const bool edge_first = patch == Patch::parted && !probes_meet_map(witnesses);
    if (edge_first && straight_edge(aim, witnesses, out)) return;
    if (patch == Patch::mixed || patch == Patch::parted) {
        rest_region.reset(footprint_, footprint_.square(), std::nullopt, 1.0, 0);
        Region* const whole[] = {&rest_region};
        refine(aim, whole, witnesses, media, frame, out, edge_first ? Unsettled::map : Unsettled::edge_or_map);
    }
}

bool FootprintIntegrator::probes_meet_map(std::span<const Probe* const> witnesses) const {
    return std::any_of(witnesses.begin(), witnesses.end(), [&](const Probe* p) {
        return p->hit->hit && p->hit->hit->object_id == scene::kBackgroundObjectId && footprint_.within_truncation(p->x_rad, p->y_rad);
    });
}

bool FootprintIntegrator::cells_meet_map(const Region& region) const {
    return std::any_of(region.nodes.begin(), region.nodes.end(), [](const Region::Node& n) {
        return n.weight > 0.0 && n.seen.hit && n.seen.echo.object_id == scene::kBackgroundObjectId;
    });
}

void FootprintIntegrator::map_sub_rays(const BeamAim& aim, const Region& region, bool media, std::uint64_t frame, BeamEchoes& out) const {
    // Where footprints overlap, their neighbours' sub-rays are this one's too.
    if (lattice_ && !media) lattice_->gather(aim.world_from_beam, aim.cell, region.excluded, region.share, out);
    else stratified(aim, map_cells_, media, frame, out, region.first_sample, region.excluded, region.share);
}

void FootprintIntegrator::stratified(const BeamAim& aim, const Footprint& cells, bool media, std::uint64_t frame, BeamEchoes& out,
                                     std::uint32_t first_draw, const std::optional<FootprintRect>& excluded, double share) const {
    thread_local std::vector<SubRay> sub_rays;
    thread_local std::vector<double> uniforms;
    sub_rays.resize(static_cast<std::size_t>(cells.samples()));
    if (!scenario_.render.jitter) {
        cells.fixed(sub_rays);
    } else {
        // Two cells per block of four draws.
        uniforms.resize(2 * sub_rays.size());
        RandomSequence draws(scenario_.render.seed, RandomStream::footprint_jitter, frame, aim.cell, first_draw);
        for (double& u : uniforms) u = draws.uniform();
        cells.jittered(sub_rays, uniforms);
    }
    if (excluded) {
        // The part accounted elsewhere is dropped; the rest carry its share, as a region's cells do.
        std::erase_if(sub_rays, [&](const SubRay& s) { return footprint_.contains(*excluded, s.offset_x_rad, s.offset_y_rad); });
        double kept = 0.0;
        for (const SubRay& s : sub_rays) kept += s.weight;
        for (SubRay& s : sub_rays) s.weight *= share / kept;
    }
    trace(aim, sub_rays, media, frame, out, first_draw);
}

void FootprintIntegrator::refine(const BeamAim& aim, std::span<Region* const> regions, std::span<const Probe* const> witnesses,
                                 bool media, std::uint64_t frame, BeamEchoes& out, Unsettled first_cells) const {
    if (first_cells != Unsettled::refine && probes_meet_map(witnesses)) {
        // Where the footprint's own probes met the recorded map, its first cells settled 3 % of
        // the time and a straight edge held 3.5 % of the times it was tried (dataset 2 over
        // Autzen, 20 frames): both cost more than they saved before the brute force below.
        map_sub_rays(aim, *regions.front(), media, frame, out);
        return;
    }
    const bool jitter = scenario_.render.jitter;
    auto place = [&](Region& r, Region::Node& n) {
        double ju = 0.5, jv = 0.5;
        if (jitter) {
            const auto u = uniform4(scenario_.render.seed, RandomStream::footprint_jitter, frame, aim.cell, r.number(n));
            ju = u[0];
            jv = u[1];
        }
        r.place(footprint_, n, n.u0 + ju * (n.u1 - n.u0), n.v0 + jv * (n.v1 - n.v0));
    };
    for (Region* r : regions) {
        r->media = media;
        for (int i = 0; i < r->base; ++i) {
            for (int j = 0; j < r->base; ++j) {
                Region::Node n{};
                n.u0 = double(i) / r->base;
                n.u1 = double(i + 1) / r->base;
                n.v0 = double(j) / r->base;
                n.v1 = double(j + 1) / r->base;
                n.i = static_cast<std::uint32_t>(i);
                n.j = static_cast<std::uint32_t>(j);
                place(*r, n);
                r->nodes.push_back(n);
            }
        }
    }
    // Echoes that earlier stages of this beam settled (a target's region, a plane patch).
    const std::size_t fixed_surface = out.surface.size();
    thread_local std::vector<BeamSurface> fixed_volume;
    fixed_volume = out.volume;
    thread_local std::vector<SurfaceEcho> scratch;
    for (;;) {
        trace_samples(aim, regions, media, frame, out);
        // The echoes as they stand: every kept leaf's, weighted by its cell.
        out.surface.resize(fixed_surface);
        out.volume = fixed_volume;
        for (std::size_t ri = 0; ri < regions.size(); ++ri) {
            Region& r = *regions[ri];
            double kept_weight = 0.0;
            for (const Region::Node& n : r.nodes)
                if (n.leaf() && n.kept) kept_weight += n.weight;
            r.scale = r.share > 0.0 && kept_weight > 0.0 ? r.share / kept_weight : 1.0;
            for (std::size_t k = 0; k < r.nodes.size(); ++k) {
                const Region::Node& n = r.nodes[k];
                if (!n.leaf() || !n.kept || n.weight <= 0.0) continue;
                const double w = n.weight * r.scale;
                if (n.seen.hit) {
                    SurfaceEcho e = n.seen.echo;
                    e.weight = w;
                    e.energy_j *= w;
                    e.sample = static_cast<std::uint32_t>((ri + 1) << 24 | k);  // 0: not a leaf's
                    out.surface.push_back(e);
                }
                for (std::uint32_t v = n.volume_first; v < n.volume_first + n.volume_count; ++v) {
                    const Region::VolumeEcho& ve = r.volume_echoes[v];
                    auto it = std::find_if(out.volume.begin(), out.volume.end(), [&](const BeamSurface& b) { return b.object_id == ve.object_id; });
                    if (it == out.volume.end()) {
                        BeamSurface b;
                        b.object_id = ve.object_id;
                        b.source = ReturnSource::volume;
                        out.volume.push_back(std::move(b));
                        it = out.volume.end() - 1;
                    }
                    it->weight += w;
                    it->echoes.push_back({ve.range_m, ve.energy_j * w, 0, ve.spread_m});
                }
            }
        }
        // Regions at their budget cannot split: what settled() would find changes nothing.
        const bool spent = std::all_of(regions.begin(), regions.end(), [](const Region* r) { return r->nodes.size() + 4 > r->max_samples; });
        if (spent && first_cells == Unsettled::refine) break;
        scratch.assign(out.surface.begin(), out.surface.end());
        if (settled(regions, witnesses, scratch, out.volume)) break;
        if (first_cells != Unsettled::refine) {
            // Unsettled at the first cells: one straight edge settles it at once, when it holds.
            const Unsettled shortcut = std::exchange(first_cells, Unsettled::refine);
            out.surface.resize(fixed_surface);
            out.volume = fixed_volume;
            Region& r = *regions.front();
            if (shortcut == Unsettled::edge_or_map && straight_edge(aim, witnesses, out, &r)) break;
            // A recorded map's discs overlap and tilt at random, so its cells never agree:
            // refinement would pay its bookkeeping for every sub-ray up to its budget and still
            // judge energies only, not where in range they fall. Brute-force sub-rays at that budget
            // cost less and place the returns better (docs/sensor.md, "Footprint and returns").
            // (Probes that met the map sent the region here before its first cells.)
            if (cells_meet_map(r)) {
                map_sub_rays(aim, r, media, frame, out);
                break;
            }
        }
        // Split the marked leaves along the axes they disagree across: two children (or four),
        // the one holding the parent's jittered sub-ray reusing it.
        bool any = false;
        for (Region* r : regions) {
            const std::size_t leaves = r->nodes.size();
            for (std::size_t k = 0; k < leaves && r->nodes.size() + 4 <= r->max_samples; ++k) {
                const Region::Node parent = r->nodes[k];
                const std::uint8_t axes = parent.want & ((parent.splits_x < kMaxSplits ? 1 : 0) | (parent.splits_y < kMaxSplits ? 2 : 0));
                if (!parent.leaf() || !parent.urgent || axes == 0) continue;
                any = true;
                r->nodes[k].first_child = static_cast<std::int32_t>(r->nodes.size());
                r->nodes[k].split = axes;
                const int along_x = axes & 1 ? 2 : 1, along_y = axes & 2 ? 2 : 1;
                const double um = 0.5 * (parent.u0 + parent.u1), vm = 0.5 * (parent.v0 + parent.v1);
                for (int a = 0; a < along_x; ++a) {
                    for (int b = 0; b < along_y; ++b) {
                        Region::Node c{};
                        c.u0 = along_x == 2 && a == 1 ? um : parent.u0;
                        c.u1 = along_x == 2 && a == 0 ? um : parent.u1;
                        c.v0 = along_y == 2 && b == 1 ? vm : parent.v0;
                        c.v1 = along_y == 2 && b == 0 ? vm : parent.v1;
                        c.splits_x = static_cast<std::uint8_t>(parent.splits_x + (along_x == 2));
                        c.splits_y = static_cast<std::uint8_t>(parent.splits_y + (along_y == 2));
                        c.i = along_x == 2 ? 2 * parent.i + static_cast<std::uint32_t>(a) : parent.i;
                        c.j = along_y == 2 ? 2 * parent.j + static_cast<std::uint32_t>(b) : parent.j;
                        auto holds = [&](double u, double v) { return u >= c.u0 && u < c.u1 && v >= c.v0 && v < c.v1; };
                        if (jitter && holds(parent.u, parent.v)) {
                            // The parent's sub-ray lies in this child: a uniform draw within it.
                            c.seen = parent.seen;
                            c.volume_first = parent.volume_first;
                            c.volume_count = parent.volume_count;
                            c.traced = true;
                            r->place(footprint_, c, parent.u, parent.v);
                        } else if (parent.adopt >= 0 && holds(r->probes[static_cast<std::size_t>(parent.adopt)].u,
                                                              r->probes[static_cast<std::size_t>(parent.adopt)].v)) {
                            // The disagreeing probe lies in this child: its sub-ray, traced already.
                            const Region::AdoptedProbe& p = r->probes[static_cast<std::size_t>(parent.adopt)];
                            r->place(footprint_, c, p.u, p.v);
                            c.seen = p.seen;
                            c.traced = true;
                        } else {
                            place(*r, c);
                        }
                        r->nodes.push_back(c);
                    }
                }
            }
        }
        if (!any) break;
    }
    // The echoes are the beam's now, no longer the regions' sub-rays'.
    for (std::size_t k = fixed_surface; k < out.surface.size(); ++k) out.surface[k].sample = 0;
}

void FootprintIntegrator::trace_samples(const BeamAim& aim, std::span<Region* const> regions, bool media, std::uint64_t frame,
                                        BeamEchoes& out) const {
    const auto& sensor = scenario_.sensor;
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    thread_local std::vector<Region::Node*> traced;
    thread_local std::vector<Region*> owner;
    thread_local std::vector<BeamSurface> volumes;
    rays.clear();
    traced.clear();
    owner.clear();
    for (Region* r : regions) {
        for (Region::Node& n : r->nodes) {
            if (n.traced) continue;
            raytrace::Ray ray;
            ray.origin_world = scenario_.mount.position_world;
            ray.direction = aim.world_from_beam * in_beam(n.x_rad, n.y_rad);
            ray.time_s = aim.time_s;
            ray.max_range_m = sensor.receiver.max_range_m;
            rays.push_back(ray);
            traced.push_back(&n);
            owner.push_back(r);
        }
    }
    hits.resize(rays.size());
    traced_.trace(rays, hits);
    out.rays += static_cast<int>(rays.size());

    for (std::size_t i = 0; i < rays.size(); ++i) {
        Region::Node& n = *traced[i];
        Region& r = *owner[i];
        n.traced = true;
        n.seen = Seen{};
        double fog = 1.0;
        if (media) {
            const std::vector<raytrace::VolumeSegment> segments = traced_.volumes_along(rays[i]);
            // Enough draws per sub-ray that no two share them (64 blocks of 4: one a segment).
            RandomSequence draws(scenario_.render.seed, RandomStream::volume_scatter, frame, aim.cell, 64 * r.number(n));
            volumes.clear();
            add_volume_echoes(segments, hits[i] ? hits[i]->range_m : sensor.receiver.max_range_m,
                              sensor.transmitter.pulse_energy_j() * sensor.optics.optics_efficiency, 1.0,
                              sensor.optics.aperture_area_m2(), receiver_, draws, volumes, kFreePaths);
            n.volume_first = static_cast<std::uint32_t>(r.volume_echoes.size());
            for (const BeamSurface& v : volumes)
                for (const Echo& e : v.echoes) r.volume_echoes.push_back({v.object_id, e.range_m, e.energy_j, e.spread_m});
            n.volume_count = static_cast<std::uint32_t>(r.volume_echoes.size()) - n.volume_first;
            for (const raytrace::VolumeSegment& seg : segments) n.seen.volumes |= std::uint64_t{1} << (seg.object_id % 64);
            if (hits[i]) fog = std::exp(-2.0 * optical_depth(segments, hits[i]->range_m));
        }
        if (!hits[i]) continue;
        const raytrace::Hit& h = *hits[i];
        n.seen.hit = true;
        n.seen.reflectance = h.reflectance;
        n.seen.echo = {h.range_m, 1.0, echo_energy_j(1.0, h.reflectance, h.cos_incidence, h.range_m, fog), 0.0, h.object_id,
                       rays[i].origin_world + h.range_m * rays[i].direction, h.normal_world, 0};
    }
}

bool FootprintIntegrator::settled(std::span<Region* const> regions, std::span<const Probe* const> witnesses,
                                  std::vector<SurfaceEcho>& echoes, const std::vector<BeamSurface>& volumes) const {
    const double gap = scenario_.sensor.receiver.return_gap_m;
    // The returns as they stand: each surface's energy and range spread, and so the energy at
    // which its pulse reaches the threshold.
    thread_local std::vector<std::uint32_t> surface_of_echo;
    thread_local std::vector<BeamSurface> surfaces;
    gather_surfaces(echoes, gap, surfaces, &surface_of_echo);
    // What the receiver tells apart: surfaces whose echoes overlap in range, or come closer than
    // the pulse's length, make one pulse in the waveform. A cell shared by two of them changes
    // nothing the receiver reports, so they are judged as one return (a cluster).
    const double resolution = 0.5 * kSpeedOfLight_mps * scenario_.sensor.transmitter.pulse_width_ns * 1e-9;
    thread_local std::vector<std::pair<double, double>> extent;
    thread_local std::vector<std::uint32_t> order, merged;
    extent.resize(surfaces.size());
    order.resize(surfaces.size());
    for (std::size_t g = 0; g < surfaces.size(); ++g) {
        double lo = surfaces[g].echoes.front().range_m, hi = lo;
        for (const Echo& e : surfaces[g].echoes) {
            lo = std::min(lo, e.range_m - e.spread_m);
            hi = std::max(hi, e.range_m + e.spread_m);
        }
        extent[g] = {lo, hi};
        order[g] = static_cast<std::uint32_t>(g);
    }
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return extent[a].first < extent[b].first; });
    merged.assign(surfaces.size(), 0);
    std::size_t clusters = 0;
    double reach = -1e300;
    for (const std::uint32_t g : order) {
        if (clusters == 0 || extent[g].first - reach > resolution) {
            ++clusters;
            reach = extent[g].second;
        }
        reach = std::max(reach, extent[g].second);
        merged[g] = static_cast<std::uint32_t>(clusters - 1);
    }
    for (std::uint32_t& g : surface_of_echo) g = merged[g];
    const std::size_t returns = clusters + volumes.size();
    thread_local std::vector<double> energy, variance, threshold, mean;
    energy.assign(returns, 0.0);
    variance.assign(returns, 0.0);
    threshold.assign(returns, 0.0);
    mean.assign(returns, 0.0);
    // Each return's energy and range spread (so the energy at which its pulse reaches the
    // threshold), its echoes taken in range order of their surfaces.
    auto each_echo = [&](auto&& f) {
        for (const std::uint32_t g : order)
            for (const Echo& x : surfaces[g].echoes) f(merged[g], x);
        for (std::size_t g = 0; g < volumes.size(); ++g)
            for (const Echo& x : volumes[g].echoes) f(clusters + g, x);
    };
    each_echo([&](std::size_t g, const Echo& x) {
        energy[g] += x.energy_j;
        mean[g] += x.energy_j * x.range_m;
    });
    thread_local std::vector<double> spread;
    spread.assign(returns, 0.0);
    for (std::size_t g = 0; g < returns; ++g)
        if (energy[g] > 0.0) mean[g] /= energy[g];
    each_echo([&](std::size_t g, const Echo& x) {
        if (energy[g] > 0.0) spread[g] += x.energy_j * ((x.range_m - mean[g]) * (x.range_m - mean[g]) + x.spread_m * x.spread_m);
    });
    for (std::size_t g = 0; g < returns; ++g)
        threshold[g] = threshold_energy_j(energy[g] > 0.0 ? std::sqrt(spread[g] / energy[g]) : 0.0);
    // Which return each leaf's surface echo went to.
    for (Region* r : regions)
        for (Region::Node& n : r->nodes) {
            n.boundary = n.urgent = false;
            n.want = 0;
            n.adopt = -1;
            n.touches = {-1, -1, -1, -1};
            n.surface = -1;
        }
    for (std::size_t k = 0; k < echoes.size(); ++k) {
        const std::uint32_t key = echoes[k].sample;
        if (key >> 24 == 0) continue;
        regions[(key >> 24) - 1]->nodes[key & 0xFFFFFFu].surface = static_cast<std::int32_t>(surface_of_echo[k]);
    }
    auto volume_return = [&](std::uint32_t object_id) -> std::int32_t {
        for (std::size_t g = 0; g < volumes.size(); ++g)
            if (volumes[g].object_id == object_id) return static_cast<std::int32_t>(clusters + g);
        return -1;
    };

    // Cells that disagree with a neighbour (or with a probe inside them) may hold a part of what
    // the other found: each is a draw of about half its cell's energy either way, adding
    // (w e / 2)^2 to the variance of the returns involved.
    auto add_uncertainty = [&](Region::Node& n, std::int32_t g, double energy_j) {
        if (g < 0 || !(energy_j > 0.0)) return;
        variance[static_cast<std::size_t>(g)] += 0.25 * energy_j * energy_j;
        n.boundary = true;
        for (std::int32_t& t : n.touches) {
            if (t == g) break;
            if (t < 0) {
                t = g;
                break;
            }
        }
    };
    auto involve = [&](const Region& r, Region::Node& a, const Seen& other, std::int32_t other_surface,
                       std::uint32_t other_volume_first, std::uint32_t other_volume_count) {
        const double w = a.weight * r.scale;
        // Its cell may hold the other's surface (and the other's cell its own: counted from there).
        if (a.surface >= 0) add_uncertainty(a, a.surface, w * a.seen.echo.energy_j);
        if (other.hit) add_uncertainty(a, other_surface, w * other.echo.energy_j);
        for (std::uint32_t v = a.volume_first; v < a.volume_first + a.volume_count; ++v)
            add_uncertainty(a, volume_return(r.volume_echoes[v].object_id), w * r.volume_echoes[v].energy_j);
        for (std::uint32_t v = other_volume_first; v < other_volume_first + other_volume_count; ++v)
            add_uncertainty(a, volume_return(r.volume_echoes[v].object_id), w * r.volume_echoes[v].energy_j);
    };
    constexpr double kAcross = 1e-9;  // a step across a cell's side: far below the finest cell
    for (Region* region : regions) {
        Region& r = *region;
        for (std::size_t k = 0; k < r.nodes.size(); ++k) {
            if (!r.nodes[k].leaf() || !r.nodes[k].kept) continue;
            for (int side = 0; side < 4; ++side) {
                Region::Node& n = r.nodes[k];
                const bool across_x = side < 2;  // right, left: neighbours along x
                const double um = 0.5 * (n.u0 + n.u1), vm = 0.5 * (n.v0 + n.v1);
                const Region::Node* m = side == 0   ? r.leaf_at(n.u1 + kAcross, vm)
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
                if (agree(n.seen, m->seen, gap)) continue;
                Region::Node& other = r.nodes[static_cast<std::size_t>(m - r.nodes.data())];
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
        // Probes inside the region: a probe that met something its cell's sub-ray did not (an
        // edge's sliver between sub-rays) makes that cell uncertain by the probe's echo.
        for (std::size_t w = 0; w < witnesses.size(); ++w) {
            const Probe* p = witnesses[w];
            if (r.excluded && footprint_.contains(*r.excluded, p->x_rad, p->y_rad)) continue;
            if (!footprint_.within_truncation(p->x_rad, p->y_rad)) continue;
            if (r.witness_u.size() != witnesses.size()) {
                // Where each probe lies in the region and what it met, once per region.
                r.witness_u.resize(witnesses.size());
                r.witness_v.resize(witnesses.size());
                r.witness_seen.resize(witnesses.size());
                for (std::size_t q = 0; q < witnesses.size(); ++q) {
                    const Probe* o = witnesses[q];
                    if (!footprint_.within_truncation(o->x_rad, o->y_rad)) continue;  // never looked at
                    r.witness_u[q] = (footprint_.axis_cdf(o->x_rad) - r.cdf_x0) / r.cdf_dx;
                    r.witness_v[q] = (footprint_.axis_cdf(o->y_rad) - r.cdf_y0) / r.cdf_dy;
                    Seen& seen = r.witness_seen[q];
                    seen = Seen{};
                    if (!o->hit->hit) continue;
                    const raytrace::Hit& h = *o->hit->hit;
                    seen.hit = true;
                    seen.reflectance = h.reflectance;
                    // Its echo (an exponential) only when it disagrees, below.
                    seen.echo = {h.range_m, 1.0, -1.0, 0.0, h.object_id, o->hit->point_world, h.normal_world, 0};
                }
            }
            const double pu = r.witness_u[w], pv = r.witness_v[w];
            const Region::Node* leaf = r.leaf_at(pu, pv);
            if (!leaf || !leaf->kept) continue;
            r.witness_seen[w].volumes = leaf->seen.volumes;  // probes do not look into media
            if (agree(leaf->seen, r.witness_seen[w], gap)) continue;
            if (r.witness_seen[w].hit && r.witness_seen[w].echo.energy_j < 0.0) {
                const raytrace::Hit& h = *p->hit->hit;
                r.witness_seen[w].echo.energy_j = echo_energy_j(1.0, h.reflectance, h.cos_incidence, h.range_m, 1.0);
            }
            const Seen& probe = r.witness_seen[w];
            Region::Node& n = r.nodes[static_cast<std::size_t>(leaf - r.nodes.data())];
            // The probe's surface, if some sub-ray found it; else a return not seen yet.
            std::int32_t probe_surface = -1;
            if (probe.hit) {
                for (std::size_t e = 0; e < echoes.size() && probe_surface < 0; ++e)
                    if (echoes[e].object_id == probe.echo.object_id)
                        probe_surface = static_cast<std::int32_t>(surface_of_echo[e]);
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
                kConfidenceSigmas * 0.5 * n.weight * r.scale * probe.echo.energy_j > tolerance_ * threshold_j_)
                n.urgent = true;
        }
    }

    // Settled when every return's energy is known to the tolerance of itself, or of its pulse's
    // threshold when weaker (below it, errors decide nothing); else refine the cells bounding an
    // unsettled return (or an unseen probe's), while they can be.
    thread_local std::vector<std::uint8_t> unsettled, undecided;
    unsettled.assign(returns, 0);
    for (std::size_t g = 0; g < returns; ++g)
        unsettled[g] = kConfidenceSigmas * std::sqrt(variance[g]) > tolerance_ * std::max(energy[g], threshold[g]);
    // Whether a return is detected at all depends on its pulse's peak, so on how its energy spreads
    // in range, which its sub-rays sample: with n of them the spread (and so the threshold) is known
    // to about 1 / sqrt(n). A return that close to its threshold is undecided: all its cells split.
    undecided.assign(returns, 0);
    thread_local std::vector<int> samples_of;
    samples_of.assign(returns, 0);
    for (Region* r : regions)
        for (const Region::Node& n : r->nodes)
            if (n.leaf() && n.surface >= 0) ++samples_of[static_cast<std::size_t>(n.surface)];
    for (std::size_t g = 0; g < clusters; ++g) {
        if (samples_of[g] == 0) continue;
        const double margin = 1.5 / std::sqrt(2.0 * samples_of[g]);
        undecided[g] = std::abs(energy[g] - threshold[g]) < margin * threshold[g];
    }
    bool refinable = false;
    for (Region* r : regions) {
        if (r->nodes.size() + 4 > r->max_samples) continue;
        for (Region::Node& n : r->nodes) {
            if (!n.leaf()) continue;
            for (const std::int32_t t : n.touches)
                if (t >= 0 && unsettled[static_cast<std::size_t>(t)]) n.urgent = true;
            if (n.surface >= 0 && undecided[static_cast<std::size_t>(n.surface)]) {
                n.urgent = true;
                n.want |= 3;
            }
            const std::uint8_t axes = n.want & ((n.splits_x < kMaxSplits ? 1 : 0) | (n.splits_y < kMaxSplits ? 2 : 0));
            refinable = refinable || (n.urgent && axes != 0);
        }
    }
    return !refinable;
}

void FootprintIntegrator::trace(const BeamAim& aim, std::span<const SubRay> sub_rays, bool media, std::uint64_t frame,
                                BeamEchoes& out, std::uint32_t first_draw) const {
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

    // As a region's sub-rays draw theirs: 64 a sub-ray from its number on.
    RandomSequence volume_draws(scenario_.render.seed, RandomStream::volume_scatter, frame, aim.cell, std::uint64_t{64} * first_draw);
    for (std::size_t i = 0; i < sub_rays.size(); ++i) {
        const double weight = sub_rays[i].weight;
        double fog = 1.0;
        if (media) {
            thread_local std::vector<raytrace::VolumeSegment> volumes;
            traced_.volumes_along(rays[i], volumes);
            add_volume_echoes(volumes, hits[i] ? hits[i]->range_m : sensor.receiver.max_range_m,
                              sensor.transmitter.pulse_energy_j() * weight * sensor.optics.optics_efficiency, weight,
                              sensor.optics.aperture_area_m2(), receiver_, volume_draws, out.volume, kFreePaths);
            if (hits[i]) fog = std::exp(-2.0 * optical_depth(volumes, hits[i]->range_m));
        }
        if (!hits[i]) continue;
        const raytrace::Hit& h = *hits[i];
        out.surface.push_back({h.range_m, weight, echo_energy_j(weight, h.reflectance, h.cos_incidence, h.range_m, fog), 0.0,
                               h.object_id, rays[i].origin_world + h.range_m * rays[i].direction, h.normal_world, 0});
    }
}

namespace {

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

}  // namespace

bool FootprintIntegrator::straight_edge(const BeamAim& aim, std::span<const Probe* const> witnesses, BeamEchoes& out,
                                        const Region* sampled) const {
    const double gap = scenario_.sensor.receiver.return_gap_m;
    const double r_max = footprint_.max_offset_rad();
    const Eigen::Vector3d& origin = scenario_.mount.position_world;
    struct Point {
        Eigen::Vector2d offset;
        Seen seen;
        int side = -1;  ///< which of the two surfaces
    };
    thread_local std::vector<Point> points;
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    points.clear();
    auto seen_of = [&](const std::optional<raytrace::Hit>& hit, const Eigen::Vector3d& direction) {
        Seen seen;
        if (!hit) return seen;
        seen.hit = true;
        seen.reflectance = hit->reflectance;
        seen.cos_incidence = hit->cos_incidence;
        // Its echo (an exponential) only where it is used.
        seen.echo = {hit->range_m, 1.0, -1.0, 0.0, hit->object_id, origin + hit->range_m * direction, hit->normal_world, 0};
        return seen;
    };
    auto energy_of = [&](const Seen& s) {
        return s.echo.energy_j >= 0.0 ? s.echo.energy_j : echo_energy_j(1.0, s.reflectance, s.cos_incidence, s.echo.range_m, 1.0);
    };
    auto trace_offsets = [&](std::span<const Eigen::Vector2d> offsets, std::vector<Seen>& seen) {
        rays.resize(offsets.size());
        hits.resize(offsets.size());
        for (std::size_t i = 0; i < offsets.size(); ++i) {
            rays[i].origin_world = origin;
            rays[i].direction = aim.world_from_beam * in_beam(offsets[i].x(), offsets[i].y());
            rays[i].time_s = aim.time_s;
            rays[i].max_range_m = scenario_.sensor.receiver.max_range_m;
        }
        traced_.trace(rays, hits);
        out.rays += static_cast<int>(offsets.size());
        if (seen.size() < offsets.size()) seen.resize(offsets.size());  // never shrunk: no re-construction
        for (std::size_t i = 0; i < offsets.size(); ++i) seen[i] = seen_of(hits[i], rays[i].direction);
    };
    // Two surfaces (one may be nothing), each represented by its first point.
    std::array<const Seen*, 2> surface{nullptr, nullptr};
    thread_local std::array<Seen, 2> representative;
    auto side_of = [&](const Seen& s) {
        for (int k = 0; k < 2; ++k) {
            if (!surface[static_cast<std::size_t>(k)]) {
                representative[static_cast<std::size_t>(k)] = s;
                surface[static_cast<std::size_t>(k)] = &representative[static_cast<std::size_t>(k)];
                return k;
            }
            if (agree(*surface[static_cast<std::size_t>(k)], s, gap)) return k;
        }
        return -1;  // a third: not one edge
    };

    // The rim of the footprint, just inside its truncation, where an edge crossing it enters and
    // leaves; then the probes inside, which the edge must separate.
    constexpr int kRim = 12;
    constexpr int kBisections = 5;
    const double rim = 0.999 * r_max;
    thread_local std::vector<Eigen::Vector2d> offsets;
    thread_local std::vector<Seen> seen;
    offsets.clear();
    for (int k = 0; k < kRim; ++k) {
        const double a = 2.0 * std::numbers::pi * k / kRim;
        offsets.emplace_back(rim * std::cos(a), rim * std::sin(a));
    }
    trace_offsets(offsets, seen);
    std::array<int, kRim> rim_side{};
    for (int k = 0; k < kRim; ++k) {
        rim_side[static_cast<std::size_t>(k)] = side_of(seen[static_cast<std::size_t>(k)]);
        if (rim_side[static_cast<std::size_t>(k)] < 0) return false;
        points.push_back({offsets[static_cast<std::size_t>(k)], seen[static_cast<std::size_t>(k)], rim_side[static_cast<std::size_t>(k)]});
    }
    for (const Probe* p : witnesses) {
        if (!footprint_.within_truncation(p->x_rad, p->y_rad)) continue;
        Point q{{p->x_rad, p->y_rad}, seen_of(p->hit->hit, p->direction_world), -1};
        q.side = side_of(q.seen);
        if (q.side < 0) return false;
        points.push_back(q);
    }
    // The rim changes side exactly twice: the edge's two ends. Bisect each in angle.
    std::array<int, 2> change{-1, -1};
    int changes = 0;
    for (int k = 0; k < kRim; ++k) {
        if (rim_side[static_cast<std::size_t>(k)] == rim_side[static_cast<std::size_t>((k + 1) % kRim)]) continue;
        if (changes == 2) return false;
        change[static_cast<std::size_t>(changes++)] = k;
    }
    if (changes != 2) return false;
    std::array<double, 2> lo{}, hi{};
    for (int c = 0; c < 2; ++c) {
        lo[static_cast<std::size_t>(c)] = 2.0 * std::numbers::pi * change[static_cast<std::size_t>(c)] / kRim;
        hi[static_cast<std::size_t>(c)] = lo[static_cast<std::size_t>(c)] + 2.0 * std::numbers::pi / kRim;
    }
    const std::array<int, 2> lo_side{rim_side[static_cast<std::size_t>(change[0])], rim_side[static_cast<std::size_t>(change[1])]};
    for (int step = 0; step < kBisections; ++step) {
        offsets.clear();
        for (int c = 0; c < 2; ++c) {
            const double a = 0.5 * (lo[static_cast<std::size_t>(c)] + hi[static_cast<std::size_t>(c)]);
            offsets.emplace_back(rim * std::cos(a), rim * std::sin(a));
        }
        trace_offsets(offsets, seen);
        for (int c = 0; c < 2; ++c) {
            const int side = side_of(seen[static_cast<std::size_t>(c)]);
            if (side < 0) return false;
            points.push_back({offsets[static_cast<std::size_t>(c)], seen[static_cast<std::size_t>(c)], side});
            const double a = 0.5 * (lo[static_cast<std::size_t>(c)] + hi[static_cast<std::size_t>(c)]);
            (side == lo_side[static_cast<std::size_t>(c)] ? lo : hi)[static_cast<std::size_t>(c)] = a;
        }
    }
    const double a1 = 0.5 * (lo[0] + hi[0]), a2 = 0.5 * (lo[1] + hi[1]);
    const Eigen::Vector2d p1(rim * std::cos(a1), rim * std::sin(a1)), p2(rim * std::cos(a2), rim * std::sin(a2));
    // The chord between them, its normal pointing away from the axis: the cap beyond it.
    Eigen::Vector2d normal(-(p2 - p1).y(), (p2 - p1).x());
    normal.normalize();
    double distance = normal.dot(p1);
    if (distance < 0.0) {
        normal = -normal;
        distance = -distance;
    }
    // Which surface lies in the cap: the rim's, just past the first end towards the cap.
    const double a_cap = normal.dot(Eigen::Vector2d(std::cos(lo[0]), std::sin(lo[0]))) > normal.dot(Eigen::Vector2d(std::cos(hi[0]), std::sin(hi[0])))
                             ? lo[0] : hi[0];
    const int cap_side = a_cap == lo[0] ? lo_side[0] : 1 - lo_side[0];
    // Every probe must lie on its surface's side (those within a bisection's step of the chord
    // excepted): else the edge is not straight, or there is more than one.
    const double margin = 2.0 * rim * 2.0 * std::numbers::pi / kRim / (1 << kBisections) + 1e-3 * r_max;
    for (const Point& q : points) {
        const double along = normal.dot(q.offset) - distance;
        if (std::abs(along) < margin) continue;
        if ((along > 0.0) != (q.side == cap_side)) return false;
    }
    // Each surface takes its share of the beam (exact for a straight edge), spread over the
    // equal-energy cells on its side (the sampled region's, or the plane-patch quadrature's), each
    // of which must find that surface; a sliver holding none takes the mean of its points,
    // weighted by the beam's irradiance.
    const double cap = cap_share(distance, r_max, 0.5 * footprint_.waist_rad());
    thread_local std::vector<double> node_weight;
    offsets.clear();
    node_weight.clear();
    std::size_t sampled_cells = 0;
    if (sampled)
        for (const Region::Node& n : sampled->nodes) sampled_cells += n.leaf() && n.kept && n.weight > 0.0;
    if (sampled_cells >= edge_quadrature_.size()) {
        if (seen.size() < sampled_cells) seen.resize(sampled_cells);
        for (const Region::Node& n : sampled->nodes) {
            if (!n.leaf() || !n.kept || n.weight <= 0.0) continue;
            seen[offsets.size()] = n.seen;
            offsets.emplace_back(n.x_rad, n.y_rad);
            node_weight.push_back(n.weight);
        }
    } else {
        offsets.assign(edge_quadrature_.begin(), edge_quadrature_.end());
        trace_offsets(offsets, seen);
        node_weight.assign(offsets.size(), 1.0);
    }
    std::array<double, 2> weight_on{0.0, 0.0};
    std::array<int, 2> nodes_on{0, 0};
    thread_local std::vector<int> node_side;
    node_side.assign(offsets.size(), -1);
    for (std::size_t k = 0; k < offsets.size(); ++k) {
        const double along = normal.dot(offsets[k]) - distance;
        const int side = side_of(seen[k]);
        if (side < 0) return false;
        if (std::abs(along) >= margin && (along > 0.0) != (side == cap_side)) return false;
        node_side[k] = side;  // by what it met: within the margin, the chord may pass either way
        weight_on[static_cast<std::size_t>(node_side[k])] += node_weight[k];
        ++nodes_on[static_cast<std::size_t>(node_side[k])];
    }
    // Each side's points, irradiance-weighted: how its range spreads, and for a side no cell falls
    // on, its energy and the point nearest the axis. A side that few cells fall on (a grazing
    // sliver spanning tens of metres of range) would otherwise be as compact an echo as its cells,
    // and be detected where the whole footprint's stretched pulse is not.
    struct SidePoints {
        double weight = 0.0, energy = 0.0, range = 0.0, range2 = 0.0;
        const Point* nearest = nullptr;
        double mean() const { return range / weight; }
        double variance() const { return std::max(0.0, range2 / weight - mean() * mean()); }
    };
    std::array<SidePoints, 2> side_points;
    for (const Point& q : points) {
        if (!q.seen.hit) continue;
        SidePoints& m = side_points[static_cast<std::size_t>(q.side)];
        const double g = irradiance(q.offset.x(), q.offset.y());
        m.weight += g;
        m.range += g * q.seen.echo.range_m;
        m.range2 += g * q.seen.echo.range_m * q.seen.echo.range_m;
        if (nodes_on[static_cast<std::size_t>(q.side)] == 0) m.energy += g * energy_of(q.seen);
        if (!m.nearest || q.offset.squaredNorm() < m.nearest->offset.squaredNorm()) m.nearest = &q;
    }
    // A side whose points spread in range beyond the pulse: the shape of its echo in range, where
    // they lie on one plane, replaces its echoes (appended from `first`).
    thread_local std::vector<RangeSample> samples;
    auto resolve_in_range = [&](int side, double share, double spread, std::size_t first) {
        samples.clear();
        for (const Point& q : points)
            if (q.side == side && q.seen.hit) samples.push_back({q.offset, q.seen.echo.range_m});
        for (std::size_t k = 0; k < offsets.size(); ++k)
            if (node_side[k] == side && seen[k].hit) samples.push_back({offsets[k], seen[k].echo.range_m});
        profile_in_range(aim, samples, {normal, distance, side == cap_side}, share, spread, first, out);
    };
    for (int side = 0; side < 2; ++side) {
        const auto s = static_cast<std::size_t>(side);
        if (!surface[s]->hit) continue;
        const double share = side == cap_side ? cap : 1.0 - cap;
        const SidePoints& m = side_points[s];
        const std::size_t first = out.surface.size();
        const double spread = m.weight > 0.0 ? std::sqrt(m.variance()) : 0.0;
        if (nodes_on[s] == 0) {
            // A sliver no cell falls on takes the mean of its points.
            SurfaceEcho e = m.nearest->seen.echo;
            e.range_m = m.mean();
            e.weight = share;
            e.energy_j = share * m.energy / m.weight;
            e.sample = 0;
            e.spread_m = spread;
            out.surface.push_back(e);
            if (spread > pulse_sigma_m_) resolve_in_range(side, share, spread, first);
            continue;
        }
        // The variance of range the side's points show beyond its cells' own: each cell's echo is
        // stretched by it (variances add).
        double cell_weight = 0.0, cell_mean = 0.0, cell_square = 0.0;
        for (std::size_t k = 0; k < offsets.size(); ++k) {
            if (node_side[k] != side || !seen[k].hit) continue;
            cell_weight += node_weight[k];
            cell_mean += node_weight[k] * seen[k].echo.range_m;
            cell_square += node_weight[k] * seen[k].echo.range_m * seen[k].echo.range_m;
        }
        const double missing_variance =
            m.weight > 0.0 && cell_weight > 0.0
                ? std::max(0.0, m.variance() - (cell_square / cell_weight - std::pow(cell_mean / cell_weight, 2)))
                : 0.0;
        for (std::size_t k = 0; k < offsets.size(); ++k) {
            if (node_side[k] != side || !seen[k].hit) continue;
            SurfaceEcho e = seen[k].echo;
            e.weight = share / weight_on[s] * node_weight[k];
            e.energy_j = energy_of(seen[k]) * e.weight;
            e.sample = 0;
            e.spread_m = std::sqrt(e.spread_m * e.spread_m + missing_variance);
            out.surface.push_back(e);
        }
        if (spread > pulse_sigma_m_) resolve_in_range(side, share, spread, first);
    }
    return true;
}

void FootprintIntegrator::profile_in_range(const BeamAim& aim, std::span<const RangeSample> samples, const ChordSide& side,
                                           double share, double spread_m, std::size_t first, BeamEchoes& out) const {
    const double r_max = footprint_.max_offset_rad();
    const std::optional<RangePlane> plane = fit_range_plane(samples, r_max, std::max(pulse_sigma_m_, kPlaneFit * spread_m));
    if (!plane) return;
    double energy = 0.0;
    for (std::size_t k = first; k < out.surface.size(); ++k) energy += out.surface[k].energy_j;
    // Fine slices only where the side could reach the threshold on its own. No part of it is
    // denser in range than the whole beam's marginal across the gradient g, 1 / (sqrt(2 pi) sigma)
    // per radian: its echo peaks below the whole footprint's energy on that surface in one pulse
    // times sigma_r / (g sigma); failing that, below its densest slice's energy per metre times
    // sqrt(2 pi) sigma_r. Otherwise (ground grazed over tens of metres) one echo of the profile's
    // mean range and spread.
    const double sigma = 0.5 * footprint_.waist_rad();
    const double reach = kUndetectable * threshold_j_;
    thread_local std::vector<RangeSlice> slices;
    slices.clear();
    const bool bright = energy / share * pulse_sigma_m_ / (plane->per_rad.norm() * sigma) >= reach;
    const double depth = bright ? std::max(pulse_sigma_m_, spread_m / kSlicesPerSpread) : std::numeric_limits<double>::infinity();
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
    if (!bright || energy * densest * pulse_sigma_m_ * std::sqrt(2.0 * std::numbers::pi) < reach) slices.assign(1, one);
    // The slices lie on the plane fitted: its normal, so that they make one surface however far
    // apart (gather_surfaces), as the echoes they replace did.
    auto on_plane = [&](double x, double y) {
        return Eigen::Vector3d((plane->at_axis_m + plane->per_rad.dot(Eigen::Vector2d(x, y))) * in_beam(x, y));
    };
    const double step = 0.1 * r_max;
    const Eigen::Vector3d in_plane_normal = (on_plane(step, 0.0) - on_plane(0.0, 0.0)).cross(on_plane(0.0, step) - on_plane(0.0, 0.0));
    SurfaceEcho like = out.surface[first];
    if (in_plane_normal.norm() > 0.0) like.normal_world = (aim.world_from_beam * in_plane_normal.normalized()).cast<float>();
    like.sample = 0;
    out.surface.resize(first);
    const Eigen::Vector3d& origin = scenario_.mount.position_world;
    for (const RangeSlice& slice : slices) {
        SurfaceEcho e = like;
        e.range_m = slice.range_m;
        e.weight = share * slice.share;
        e.energy_j = energy * slice.share;
        e.spread_m = slice.spread_m;
        // (Along (1, x, y) unnormalised: a footprint's offsets are milliradians, so the point is
        // off by the range times their square, well inside what gather_surfaces allows.)
        e.point_world = origin + slice.range_m * (aim.world_from_beam * Eigen::Vector3d(1.0, slice.offset.x(), slice.offset.y() * ellipticity_));
        out.surface.push_back(e);
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
        if (!footprint_.within_truncation(p.x_rad, p.y_rad)) continue;  // a sentinel
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
    if (used.empty()) return Patch::mixed;  // nothing to go by
    if (hits == 0) return Patch::empty;
    if (hits < static_cast<int>(used.size()) || !one_object) return Patch::parted;
    if (normal_sum.norm() < 1e-9 * g_sum) return Patch::mixed;
    const Eigen::Vector3d normal = normal_sum.normalized();
    const Eigen::Vector3d centroid = point_sum / g_sum;
    const double reflectance = reflectance_sum / g_sum;
    const double plane_distance = normal.dot(centroid - origin);

    // One plane: every probe within the pulse's resolution of it, and the energy each probe saw
    // consistent with the plane's (the ratio's standard error within the tolerance).
    double q_sum = 0.0, q2_sum = 0.0, g2_sum = 0.0;
    const double gap = scenario_.sensor.receiver.return_gap_m;
    const double plane_distance2 = plane_distance * plane_distance;
    for (std::size_t k = 0; k < used.size(); ++k) {
        const Probe& p = *used[k];
        const Eigen::Vector3d& point = p.hit->point_world;
        if (std::abs(normal.dot(point - centroid)) > gap) return curved_patch(aim, used, excluded, weight, normal, out);
        const double nd = normal.dot(p.direction_world);
        if (std::abs(nd) < 1e-9) return Patch::mixed;
        // What the plane predicts the probe saw: reflectance |nd| / range^2 at the range
        // plane_distance / nd, so reflectance |nd|^3 / plane_distance^2 (one division, not three).
        const double model = reflectance * std::abs(nd) * nd * nd;
        const double seen = p.hit->seen;
        // A black patch (reflectance 0, e.g. a map point recorded with intensity 0) sees nothing
        // and the plane predicts nothing: they agree.
        const double q = model > 0.0 ? seen * plane_distance2 / model : 1.0;
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
    const Eigen::Vector3d normal_in_beam = aim.world_from_beam.transpose() * normal;  // n . (R q) = (R^T n) . q
    for (std::size_t k = 0; k < quadrature_in_beam_.size(); ++k) {
        if (excluded && footprint_.contains(*excluded, quadrature_x_[k], quadrature_y_[k])) continue;
        const double nd = normal_in_beam.dot(quadrature_in_beam_[k]);
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

FootprintIntegrator::Patch FootprintIntegrator::curved_patch(const BeamAim& aim, std::span<const Probe* const> used,
                                                             const std::optional<FootprintRect>& excluded, double weight,
                                                             const Eigen::Vector3d& normal, BeamEchoes& out) const {
    // A recorded map's discs overlap and tilt at random: its returns' structure in range is what
    // its footprints' sub-rays are for (refine), not a surface to fit.
    if (used.front()->hit->hit->object_id == scene::kBackgroundObjectId) return Patch::mixed;
    // One surface: the probes, in range order, each on the tangent planes of the next (as the
    // sub-rays of one return are), of one material within the contrast a cell tolerates.
    const double gap = scenario_.sensor.receiver.return_gap_m;
    const Eigen::Matrix3d beam_from_world = aim.world_from_beam.transpose();
    thread_local std::vector<SurfaceEcho> chain;
    thread_local std::vector<SurfaceSample> samples;
    chain.clear();
    samples.clear();
    float lo = used.front()->hit->hit->reflectance, hi = lo;
    for (const Probe* p : used) {
        const raytrace::Hit& h = *p->hit->hit;
        lo = std::min(lo, h.reflectance);
        hi = std::max(hi, h.reflectance);
        chain.push_back({h.range_m, 0.0, 0.0, 0.0, h.object_id, p->hit->point_world, h.normal_world, 0});
        samples.push_back({p->x_rad, p->y_rad, p->irradiance, h.range_m, beam_from_world * p->direction_world,
                           beam_from_world * h.normal_world.cast<double>(), h.reflectance});
    }
    if (hi > kMaterialContrast * lo) return Patch::mixed;
    std::sort(chain.begin(), chain.end(), [](const SurfaceEcho& a, const SurfaceEcho& b) { return a.range_m < b.range_m; });
    for (std::size_t k = 1; k < chain.size(); ++k)
        if (!same_surface(chain[k - 1], chain[k], gap)) return Patch::mixed;
    std::span<const PatchNode> nodes = curved_nodes_;
    thread_local std::vector<PatchNode> kept;
    if (excluded) {
        kept.clear();
        for (const PatchNode& n : curved_nodes_)
            if (!footprint_.contains(*excluded, n.x_rad, n.y_rad)) kept.push_back(n);
        nodes = kept;
    }
    const std::optional<CurvedPatch> patch = fit_curved_patch(samples, nodes, footprint_.max_offset_rad(), gap);
    if (!patch || patch->range_m > scenario_.sensor.receiver.max_range_m) return Patch::mixed;
    const double range = patch->range_m;
    const double energy = echo_energy_j(weight, 1.0, 1.0, range, 1.0) * (range * range + aperture_radius2_) * patch->seen;
    out.surface.push_back({range, weight, energy, patch->spread_m, chain.front().object_id,
                           scenario_.mount.position_world + range * aim.world_from_beam.col(0), normal.cast<float>()});
    return Patch::plane;
}

}  // namespace ladarsim::sensor_model
