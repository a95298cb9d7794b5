#pragma once
// The energy a beam's footprint sends back, integrated over the scene with as few rays as the
// requested accuracy allows (docs/physics.md, "Adaptive footprints").
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/beam_receiver.h"
#include "ladarsim/sensor_model/curved_patch.h"
#include "ladarsim/sensor_model/edge_profile.h"
#include "ladarsim/sensor_model/footprint.h"
#include "ladarsim/sensor_model/scenario.h"

namespace ladarsim::sensor_model {

/// The echo of one sub-ray, or of a whole patch of one surface.
struct SurfaceEcho {
    double range_m;
    double weight;    ///< share of the beam's energy
    double energy_j;  ///< reaching the detector
    double spread_m;  ///< standard deviation of the range across a patch; 0 for a sub-ray
    std::uint32_t object_id;
    Eigen::Vector3d point_world;
    Eigen::Vector3f normal_world;
    std::uint32_t sample = 0;  ///< which sub-ray made it, for the integrator's bookkeeping
};

/// Groups echoes (sorted here by object and range) into the distinct surfaces along a beam, each
/// of one object. Two of its echoes, neighbours in range, are one surface when within `gap_m`, or
/// when they lie on one continuous surface: each within the gap (plus a bend of 5 deg over their
/// separation) of the other's tangent plane (a surface seen at grazing incidence spans metres in
/// range and would otherwise break into one return per sub-ray). Each echo's pulse is stretched to
/// reach half-way to its neighbours in range, so that the result does not depend on how densely
/// the surface was sampled. Echoes of different objects are never one surface, however close: their
/// pulses merge in the waveform, which names a merged return after the object that sets its range.
/// With `surface_of_echo`, also which surface each echo (in the sorted order) went to.
std::vector<BeamSurface> gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m,
                                         std::vector<std::uint32_t>* surface_of_echo = nullptr);
/// The same into `surfaces`, whose elements (and their echo lists) are reused.
void gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m, std::vector<BeamSurface>& surfaces,
                     std::vector<std::uint32_t>* surface_of_echo = nullptr);

/// Where one beam points and when it fires.
struct BeamAim {
    Eigen::Matrix3d world_from_beam;  ///< x along the beam, y left, z up
    double time_s;
    std::uint32_t cell;               ///< raster cell index: keys the beam's random draws
};

/// A probe ray's hit, with what the plane test asks of it found once for every beam whose
/// footprint the probe falls in (some 25).
struct ProbeHit {
    std::optional<raytrace::Hit> hit;
    Eigen::Vector3d point_world = Eigen::Vector3d::Zero();  ///< origin + range_m * direction
    double seen = 0.0;  ///< reflectance * cos_incidence / range_m^2: the energy it saw, but constants
    /// Fills the fields above from `hit` of a probe leaving `origin` along `direction`.
    void set(const std::optional<raytrace::Hit>& h, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
        hit = h;
        if (!h) return;
        point_world = origin + h->range_m * direction;
        seen = h->reflectance * h->cos_incidence / (h->range_m * h->range_m);
    }
};

/// A ray traced ahead for a beam: the beam's own axis, a neighbouring beam's axis that falls
/// inside its footprint, or an extra ray where the raster leaves the footprint uncovered; or a
/// sentinel, a neighbouring axis just beyond the footprint's truncation.
struct Probe {
    double x_rad, y_rad;  ///< offset from the beam axis, in footprint coordinates
    double irradiance;    ///< the beam's relative irradiance there, exp(-2 r^2 / w^2)
    Eigen::Vector3d direction_world;
    const ProbeHit* hit;
};

class SubRayLattice;
class TargetLattice;

/// What one beam met, before the receiver.
struct BeamEchoes {
    std::vector<SurfaceEcho> surface;
    std::vector<BeamSurface> volume;
    int rays = 0;  ///< traced for this beam after its probes (a measure of cost)
};

/// Integrates footprints in one of two ways:
///  - fixed: `footprint_samples` stratified sub-rays per beam (the brute-force reference);
///  - adaptive (footprint_samples = 0): probes (the beam's axis and its neighbours' axes) decide
///    whether the footprint lies on one plane, then integrated without rays; objects small enough
///    to hide between probes, or moving, are found by testing the beam's cone against their
///    bounding spheres and sampled only inside the part of the footprint they can occupy (with
///    seeds, rays at points of their surfaces, as witnesses there); media are
///    sampled only where the cone meets them. Where sampling is needed, cells of equal energy (2 x 2
///    to start, 4 x 4 in a target's outline) split, along the axis across which they disagree, where neighbouring sub-rays, or a
///    probe and the sub-ray of its cell, disagree (another object, another surface, nothing, another
///    medium, or half the echo), until what the receiver reports is settled: each return's energy known to
///    `footprint_tolerance` of itself, or of its (stretched) pulse's threshold when weaker
///    (docs/sensor.md, "Footprint and returns"). A lone target takes its line's shared sub-rays over
///    it (TargetLattice) where they hold it, else, bright enough to spend the outline's budget
///    anyway, one grid of it; a footprint over a recorded map takes brute force.
class FootprintIntegrator {
public:
    FootprintIntegrator(const Scenario& scenario, const raytrace::TracedScene& traced, const BeamReceiver& receiver);

    bool adaptive() const { return adaptive_; }
    const Footprint& footprint() const { return footprint_; }
    /// The beam's elevation divergence over its azimuth divergence.
    double ellipticity() const { return ellipticity_; }
    /// Footprint coordinates of a direction given in beam coordinates (x along the beam).
    Eigen::Vector2d offset_of(const Eigen::Vector3d& in_beam) const;
    /// Beam coordinates of a footprint offset.
    Eigen::Vector3d in_beam(double x_rad, double y_rad) const;
    /// The beam's irradiance at a footprint offset, relative to its axis.
    double irradiance(double x_rad, double y_rad) const;

    /// Where a footprint over a recorded map takes brute force (without media), it takes the
    /// lattice's shared sub-rays instead of tracing its own (null: its own). Set before rendering.
    void share_sub_rays(const SubRayLattice* lattice) { lattice_ = lattice; }
    /// Where a lone target is sampled (without media), its line's shared sub-rays over it instead
    /// of its own where the lattice holds it (null: its own). Set before rendering.
    void share_target_sub_rays(const TargetLattice* lattice) { target_lattice_ = lattice; }
    /// Strata along each axis of a bright lone target's grid (its square ~ map_samples()).
    int grid_base() const { return grid_base_; }
    /// Sub-rays a footprint over a recorded map (or a target's outline) takes at this tolerance.
    std::size_t map_samples() const { return outline_samples_; }
    /// Echo energy of a sub-ray carrying `weight` of the beam that meets a surface (fog: the two-way
    /// transmission of media on the way).
    double echo_energy_j(double weight, double reflectance, double cos_incidence, double range_m, double fog) const;

    /// Echoes of one beam. `probes` (adaptive only) start with the beam's own axis.
    void integrate(const BeamAim& aim, std::span<const Probe> probes, std::uint64_t frame, BeamEchoes& out) const;

    /// One rectangle of the footprint being refined, with its tree of cells (defined in the .cpp).
    struct Region;

private:
    /// What a region's first cells try when they do not settle, before they are refined: nothing;
    /// one straight edge (straight_edge, a whole footprint without media or targets) and then
    /// brute-force sub-rays (the shared lattice's, where there is one) where the cells meet a
    /// recorded map; or only the latter. Where the footprint's probes meet the map, the first
    /// cells are skipped for the brute force.
    enum class Unsettled { refine, edge_or_map, map };
    /// Refines the regions together until the returns they give, with the echoes already in
    /// `out`, are settled; their echoes are appended to `out`. `witnesses`: probes whose hits the
    /// sub-rays of their cells must agree with. `first_cells`: the shortcut for one region.
    void refine(const BeamAim& aim, std::span<Region* const> regions, std::span<const Probe* const> witnesses, bool media,
                std::uint64_t frame, BeamEchoes& out, Unsettled first_cells = Unsettled::refine) const;
    /// What the integrator knows ahead of a mesh object met as a target.
    struct TargetShape {
        std::vector<Eigen::Vector3d> seed_points;  ///< facet centroids (model coordinates) tried as seeds
        double max_reflectance = 0.0;              ///< of its materials: bounds its echo
    };
    /// Appends the footprint offsets of the points of target `b` (of its seed candidates, `shape`)
    /// nearest the beam's axis, those inside the truncation.
    void seed_offsets(const raytrace::ObjectBounds& b, const TargetShape& shape, const Eigen::Matrix3d& beam_from_world,
                      std::vector<Eigen::Vector2d>& out) const;
    /// Whether a region's sub-rays met the recorded map.
    bool cells_meet_map(const Region& region) const;
    /// Whether the probes inside the footprint met the recorded map.
    bool probes_meet_map(std::span<const Probe* const> witnesses) const;
    /// A region over the recorded map by brute force: the shared lattice's sub-rays where there is
    /// one (and no medium), else its own stratified ones at the map's budget.
    void map_sub_rays(const BeamAim& aim, const Region& region, bool media, std::uint64_t frame, BeamEchoes& out) const;
    /// Traces the sub-rays of the regions not traced yet.
    void trace_samples(const BeamAim& aim, std::span<Region* const> regions, bool media, std::uint64_t frame, BeamEchoes& out) const;
    /// Whether the returns are settled; if not, marks the sub-rays to split. `echoes` is scratch.
    bool settled(std::span<Region* const> regions, std::span<const Probe* const> witnesses,
                 std::vector<SurfaceEcho>& echoes, const std::vector<BeamSurface>& volumes) const;
    /// Traces one sub-ray in each of the stratified cells of `cells` (jittered when the render is,
    /// by draws from `first_draw` on), appending their echoes: outside `excluded` only, those then
    /// carrying `share` of the beam.
    void stratified(const BeamAim& aim, const Footprint& cells, bool media, std::uint64_t frame, BeamEchoes& out,
                    std::uint32_t first_draw, const std::optional<FootprintRect>& excluded, double share) const;
    /// Traces sub-rays, appending their echoes (media draws from 64 x `first_draw` on).
    void trace(const BeamAim& aim, std::span<const SubRay> sub_rays, bool media, std::uint64_t frame, BeamEchoes& out,
               std::uint32_t first_draw) const;
    /// What the probes make of a footprint: nothing, one plane (or curved surface), something to
    /// refine, or something parted from nothing or from another object (likely a straight edge).
    enum class Patch { empty, plane, mixed, parted };
    /// The footprint outside `excluded` (share `weight`) as one plane, from the probes outside it.
    Patch plane_patch(const BeamAim& aim, std::span<const Probe> probes, const std::optional<FootprintRect>& excluded,
                      double weight, BeamEchoes& out) const;
    /// Where the probes' points leave every plane by more than the receiver's resolution (a grazing
    /// footprint on curved or faceted ground): the footprint as one curved or folded surface on the
    /// probes' facets (fit_curved_patch), when the probes (`used`, all on one object, not a
    /// recorded map) make one surface of one material; `normal` the probes' mean normal.
    Patch curved_patch(const BeamAim& aim, std::span<const Probe* const> used, const std::optional<FootprintRect>& excluded,
                       double weight, const Eigen::Vector3d& normal, BeamEchoes& out) const;
    /// The footprint as two surfaces (one may be nothing) parted by one straight edge: the rim of
    /// the footprint is sampled for the edge's two ends (each then bisected), every probe must lie
    /// on its surface's side of the chord between them, and each surface takes the beam's exact
    /// share beyond or before the chord (a closed form of the truncated Gaussian), spread over the
    /// cells of `sampled` (a whole footprint's first cells, when there are enough) or the
    /// equal-energy quadrature on its side. False (and nothing appended) where that does not hold:
    /// a corner, a curved edge, more surfaces.
    bool straight_edge(const BeamAim& aim, std::span<const Probe* const> witnesses, BeamEchoes& out,
                       const Region* sampled = nullptr) const;
    /// Replaces one surface's echoes in `out` (from `first` on: `share` of the beam, their points
    /// `samples` spreading `spread_m` in range) by the range profile of the plane those lie on
    /// over `side` of the footprint (edge_profile.h), their energy kept; nothing changes where
    /// they do not lie on one plane.
    void profile_in_range(const BeamAim& aim, std::span<const RangeSample> samples, const ChordSide& side, double share,
                          double spread_m, std::size_t first, BeamEchoes& out) const;
    /// Echo energy at which a pulse stretched by a range spread of `spread_m` peaks at the threshold.
    double threshold_energy_j(double spread_m) const;

    const Scenario& scenario_;
    const raytrace::TracedScene& traced_;
    const BeamReceiver& receiver_;
    bool adaptive_;
    double tolerance_;
    std::size_t outline_samples_;  ///< a target outline's (and a map footprint's) sub-ray budget at this tolerance
    double ellipticity_;
    double small_object_rad_;   ///< objects subtending less than this are sampled explicitly
    double pulse_sigma_m_;      ///< the pulse's standard deviation, in range
    double threshold_j_ = 0.0;  ///< threshold_energy_j(0): an unstretched pulse's, found once
    int grid_base_;             ///< cells along each axis of a bright lone target's grid (grid_base_^2 ~ outline_samples_)
    double aperture_radius2_;   ///< r_a^2 of the range equation's view factor
    Footprint footprint_;
    Footprint map_cells_;  ///< stratified cells for a footprint that meets a recorded map (outline_samples_)
    std::vector<Eigen::Vector3d> quadrature_in_beam_;  ///< directions integrating a plane patch
    std::vector<double> quadrature_x_, quadrature_y_;
    std::vector<Eigen::Vector2d> edge_quadrature_;     ///< equal-energy cells spreading a straight edge's sides
    std::vector<PatchNode> curved_nodes_;              ///< directions integrating a curved patch
    const SubRayLattice* lattice_ = nullptr;
    const TargetLattice* target_lattice_ = nullptr;
    std::unordered_map<std::uint32_t, TargetShape> target_shapes_;  ///< by object id
};

}  // namespace ladarsim::sensor_model
