#include "ladarsim/sensor_model/footprint/footprint_integrator.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "beam_cone.h"
#include "cell_refinement.h"
#include "curved_patch.h"
#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/target_lattice.h"
#include "map_discs.h"
#include "map_rows.h"
#include "map_scanline.h"
#include "plane_patch.h"
#include "recorded_map_sampling.h"
#include "straight_edge.h"
#include "stratified_sub_rays.h"

namespace ladarsim::sensor_model {

namespace {

/// Where the sampling of the part of the footprint left to the background starts its draws, so
/// that they never repeat those of a target's region in the same beam.
constexpr std::uint32_t kComplementSamples = 1u << 23;  // above any region's cell numbers
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
/// Lines across a footprint over a recorded map.
constexpr int kMapLines = 32;
/// Lines a raster row shares over a recorded map, per step between its beams (MapRows).
constexpr int kMapLinesPerPitch = 2;

}  // namespace

struct FootprintIntegrator::Strategies {
    Strategies(const FootprintSettings& settings, const Sensor& sensor, const std::vector<scene::SceneObject>& objects,
               const scene::BackgroundMap* map_discs, const raytrace::TracedScene& traced, const EchoRadiometry& radiometry)
        : context(settings, sensor, traced, radiometry),
          cone(context, objects),
          reference(context, context.shape.footprint()),
          map(context),
          curved(context),
          plane(context, curved),
          edge(context),
          outline_cells(context, {kOutlineBase, context.outline_samples, true}, nullptr, nullptr),
          target_grid(context, {context.grid_base, static_cast<std::size_t>(context.grid_base * context.grid_base), true}, nullptr,
                      nullptr),
          medium_cells(context, {kOutlineBase, kFootprintSamples, false}, nullptr, &map),
          rest_cells(context, {kFootprintBase, kFootprintSamples, false}, nullptr, &map),
          footprint_cells(context, {kFootprintBase, kFootprintSamples, false}, &edge, &map) {
        if (map_discs && !map_discs->points_world.empty()) discs.emplace(*map_discs, settings.origin_world);
        if (discs && !context.adaptive && settings.map_lines > 0)
            map_reference.emplace(context, *discs, settings.map_lines, std::max(1, settings.samples / settings.map_lines), &cone);
        if (discs && context.adaptive) {
            map_lines.emplace(context, *discs, kMapLines, 0);
            map.integrate_along_lines(&*map_lines);
        }
    }

    /// Targets are sampled where they can be; the rest of the footprint, like a footprint without
    /// targets, is one plane patch when the probes agree, and refined otherwise (always in media).
    void integrate_targets(const BeamSetting& beam, const TargetsInCone& targets, std::vector<const Probe*>& witnesses,
                           BeamEchoes& out) const;

    FootprintContext context;
    BeamCone cone;
    StratifiedSubRays reference;  ///< fixed sub-rays: the brute-force reference
    RecordedMapSampling map;
    CurvedPatch curved;
    PlanePatch plane;
    StraightEdge edge;
    CellRefinement outline_cells;    ///< a target's outline, 4 x 4 to start
    CellRefinement target_grid;      ///< a bright lone target's, its whole budget at once
    CellRefinement medium_cells;     ///< a footprint in media: a cloud's sliver shows only to sub-rays, 4 x 4 to start
    CellRefinement rest_cells;       ///< what targets leave, or a footprint whose edge failed: the map first
    CellRefinement footprint_cells;  ///< a whole footprint: an edge or the map at its first cells
    const TargetLattice* target_lattice = nullptr;
    std::optional<MapDiscs> discs;
    std::optional<MapScanline> map_reference;  ///< fixed sub-rays' counterpart over a recorded map (settings.map_lines)
    std::optional<MapScanline> map_lines;      ///< the recorded map's footprints where the map strategy takes them
    std::optional<MapRows> map_rows;           ///< map_lines' visibility shared by a row's beams, where the raster allows
    const FootprintStrategy& over_map() const { return map_rows ? static_cast<const FootprintStrategy&>(*map_rows) : *map_lines; }
};

FootprintIntegrator::FootprintIntegrator(const FootprintSettings& settings, const Sensor& sensor,
                                         const std::vector<scene::SceneObject>& objects, const scene::BackgroundMap* map,
                                         const raytrace::TracedScene& traced, const EchoRadiometry& radiometry)
    : s_(std::make_unique<Strategies>(settings, sensor, objects, map, traced, radiometry)) {}

FootprintIntegrator::~FootprintIntegrator() = default;

bool FootprintIntegrator::adaptive() const { return s_->context.adaptive; }
const BeamShape& FootprintIntegrator::shape() const { return s_->context.shape; }
int FootprintIntegrator::grid_base() const { return s_->context.grid_base; }
std::size_t FootprintIntegrator::map_samples() const { return s_->context.outline_samples; }
void FootprintIntegrator::share_target_sub_rays(const TargetLattice* lattice) { s_->target_lattice = lattice; }

bool FootprintIntegrator::share_map_rows(const ScanPattern& raster) {
    if (!s_->map_lines || !MapRows::applicable(raster, s_->context.shape)) return false;
    s_->map_rows.emplace(s_->context, *s_->discs, raster, kMapLinesPerPitch);
    s_->outline_cells.measure_map_by(&*s_->map_rows);
    s_->target_grid.measure_map_by(&*s_->map_rows);
    return true;
}

void FootprintIntegrator::start_map_row(int row, const Eigen::Matrix3d& world_from_gimbal) {
    if (s_->map_rows) s_->map_rows->start_row(row, world_from_gimbal);
}

void FootprintIntegrator::integrate(const BeamAim& aim, std::span<const Probe> probes, std::uint64_t frame, BeamEchoes& out) const {
    out.surface.clear();
    out.volume.clear();
    out.rays = 0;
    const FootprintContext& context = s_->context;
    const FootprintPart whole{context.shape.footprint().square(), std::nullopt, 1.0, 0};
    if (!context.adaptive) {
        const BeamSetting beam{aim, probes, {}, context.traced.has_volumes(), frame, 0};
        if (!s_->map_reference || s_->map_reference->integrate(beam, whole, out).outcome == Outcome::declined)
            s_->reference.integrate(beam, whole, out);
        return;
    }
    thread_local TargetsInCone targets;
    s_->cone.find(aim, targets);
    // Probes are witnesses of what the sub-rays of their cells must find, unless they met a moving
    // object (a neighbour's probe flew at another time).
    thread_local std::vector<const Probe*> witnesses;
    witnesses.clear();
    for (const Probe& p : probes) {
        const bool moving = p.hit->hit && std::any_of(targets.objects.begin(), targets.objects.end(), [&](const raytrace::ObjectBounds& b) {
            return b.moving && b.object_id == p.hit->hit->object_id;
        });
        if (!moving) witnesses.push_back(&p);
    }
    const BeamSetting beam{aim, probes, witnesses, targets.media, frame, targets.lone_id};
    if (targets.outline) {
        s_->integrate_targets(beam, targets, witnesses, out);
        return;
    }
    if (targets.media) {
        s_->medium_cells.integrate(beam, whole, out);
        return;
    }
    if (s_->map_lines && s_->map.met_by(witnesses)) {
        s_->over_map().integrate(beam, whole, out);
        return;
    }
    const Outcome patch = s_->plane.integrate(beam, whole, out).outcome;
    if (patch == Outcome::empty) {
        // Nothing inside; a sentinel that met something: its edge may cross the rim.
        const bool near = std::any_of(probes.begin(), probes.end(), [&](const Probe& p) {
            return p.hit->hit && !context.shape.footprint().within_truncation(p.x_rad, p.y_rad);
        });
        if (near) s_->edge.integrate(beam, whole, out);
        return;
    }
    // Probes parted between something and nothing, or between two objects, are a straight edge
    // (a skyline, a wall against the ground) all but always: over the horizon 17 k such footprints
    // in 60 frames tried one after their first cells and 10 failed; the first cells settled none.
    // So the edge is tried first, and refinement follows only where it fails.
    const bool edge_first = patch == Outcome::parted && !s_->map.met_by(witnesses);
    if (edge_first && s_->edge.integrate(beam, whole, out).outcome == Outcome::integrated) return;
    if (patch == Outcome::declined || patch == Outcome::parted) (edge_first ? s_->rest_cells : s_->footprint_cells).integrate(beam, whole, out);
}

void FootprintIntegrator::Strategies::integrate_targets(const BeamSetting& beam, const TargetsInCone& targets,
                                                        std::vector<const Probe*>& witnesses, BeamEchoes& out) const {
    // Seeds: a ray at a point of each target's surface (where the beam is brightest), at this
    // beam's time, is a witness too: the first cells of an outline are a few sub-rays across a
    // box a thin or sparse target barely fills (a bird's wing edge-on, a quadcopter's arms, a
    // drone in one rectangle with the birds around it), and cells that all meet nothing agree and
    // settle; a seed that met the target splits its cell until it is a cell's sub-ray itself.
    // (Traced only where refinement will ask them: a bright lone target's grid does not.)
    thread_local std::vector<Probe> seeds;
    thread_local std::vector<ProbeHit> seed_hits;
    bool seeded = false;
    // Seeding may grow `witnesses` and so leave `beam.witnesses` stale: strategies that read the
    // witnesses after it take with_seeds()'s setting (the plane patch reads only the probes).
    auto with_seeds = [&] {
        if (!std::exchange(seeded, true)) cone.add_seeds(beam.aim, targets, seeds, seed_hits, witnesses, out);
        return BeamSetting{beam.aim, beam.probes, witnesses, beam.media, beam.frame, beam.lone_target_id};
    };
    const FootprintPart outline{*targets.outline, std::nullopt, 0.0, 0};
    Integration shared{Outcome::declined};
    if (targets.count == 1 && !beam.media && target_lattice)
        shared = map_rows ? target_lattice->integrate_over_map(beam, outline, *map_rows, out) : target_lattice->integrate(beam, outline, out);
    double sampled = shared.share;  // its line's sub-rays over it
    if (shared.outcome != Outcome::integrated) {
        const bool bright_lone = targets.count == 1 && targets.brightest_j >= kBrightTargetThresholds * context.threshold_j;
        sampled = bright_lone ? target_grid.integrate(beam, outline, out).share : outline_cells.integrate(with_seeds(), outline, out).share;
    }
    const double rest = 1.0 - sampled;
    const FootprintPart rest_part{context.shape.footprint().square(), *targets.outline, rest, kComplementSamples};
    if (rest > 1e-9 && !beam.media && map_lines && map.met_by(witnesses)) {
        over_map().integrate(beam, rest_part, out);
        return;
    }
    const Outcome patch = rest > 1e-9 && !beam.media ? plane.integrate(beam, rest_part, out).outcome : Outcome::declined;
    if (rest > 1e-9 && (patch == Outcome::declined || patch == Outcome::parted)) rest_cells.integrate(with_seeds(), rest_part, out);
}

}  // namespace ladarsim::sensor_model
