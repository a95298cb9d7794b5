#pragma once
// The energy a beam's footprint sends back, integrated over the scene with as few rays as the
// requested accuracy allows (docs/physics.md, "Adaptive footprints"; docs/sensor.md, "Footprint
// and returns").
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/scene/scene.h"
#include "ladarsim/sensor_model/footprint/beam.h"
#include "ladarsim/sensor_model/footprint/beam_shape.h"
#include "ladarsim/sensor_model/footprint/footprint_settings.h"
#include "ladarsim/sensor_model/sensor/scan_pattern.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/sensor_model/signal/echo_radiometry.h"

namespace ladarsim::sensor_model {

class TargetLattice;

/// Chooses, beam by beam, among strategies (footprint_strategy.h):
///  - fixed (settings.samples > 0): stratified sub-rays (the brute-force reference);
///  - adaptive: probes (the beam's axis and its neighbours' axes) tell whether the footprint lies
///    on one plane (a plane patch) or one curved surface (a curved patch), both without rays, or
///    is parted by one straight edge; objects small enough to hide between probes, or moving
///    (targets), are found by testing the beam's cone against their bounding spheres and sampled
///    only inside the part of the footprint they can occupy: a lone target by its line's shared
///    sub-rays (TargetLattice) where they hold it, else by cell refinement (with seeds, rays at
///    points of their surfaces, as witnesses), bright enough to spend the outline's budget anyway
///    by one grid of it; media are sampled only where the cone meets them; what is left is
///    refined in cells of equal energy, and a footprint over a recorded map takes brute force.
class FootprintIntegrator {
public:
    /// `objects`: the scene's, whose meshes give targets' seeds; `map`: its recorded map (null: none).
    FootprintIntegrator(const FootprintSettings& settings, const Sensor& sensor, const std::vector<scene::SceneObject>& objects,
                        const scene::BackgroundMap* map, const raytrace::TracedScene& traced, const EchoRadiometry& radiometry);
    ~FootprintIntegrator();
    FootprintIntegrator(const FootprintIntegrator&) = delete;
    FootprintIntegrator& operator=(const FootprintIntegrator&) = delete;

    bool adaptive() const;
    const BeamShape& shape() const;
    /// Cells along each axis of a bright lone target's grid (its square ~ map_samples()).
    int grid_base() const;
    /// Sub-rays a footprint over a recorded map (or a target's outline) takes at this tolerance.
    std::size_t map_samples() const;

    /// Where a lone target is sampled (without media), its line's shared sub-rays over it instead
    /// of its own where the lattice holds it (null: its own). Set before rendering.
    void share_target_sub_rays(const TargetLattice* lattice);

    /// Over a recorded map, the visibility along lines each row of `raster` shares (MapRows), where
    /// its rows allow it. Set before rendering; true where they do.
    bool share_map_rows(const ScanPattern& raster);
    /// The map's shared lines of `row` for a frame (after share_map_rows, before the row's beams):
    /// `world_from_gimbal` the gimbal's frame then. Rows are independent of each other.
    void start_map_row(int row, const Eigen::Matrix3d& world_from_gimbal);

    /// Echoes of one beam. `probes` (adaptive only) start with the beam's own axis.
    void integrate(const BeamAim& aim, std::span<const Probe> probes, std::uint64_t frame, BeamEchoes& out) const;

private:
    struct Strategies;
    std::unique_ptr<Strategies> s_;
};

}  // namespace ladarsim::sensor_model
