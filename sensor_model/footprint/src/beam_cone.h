#pragma once
// The small or moving objects (targets) and media a beam's cone can touch at its time, their
// outline in its footprint, and seeds: rays at points of their surfaces.
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "footprint_context.h"
#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::sensor_model {

/// What the integrator knows ahead of a mesh object met as a target: points of its surface tried
/// as seeds, where its animation moves them, and the brightest echo it can send.
struct TargetSeeds {
    std::vector<Eigen::Vector3d> points;  ///< facet centroids at rest (model coordinates)
    /// The animation part each point's facet belongs to (-1: none, it moves with the model).
    std::vector<std::int32_t> part;
    /// Set when some part moves: points are placed at each beam's time.
    std::optional<scene::PartMotions> motions;
    /// With `motions`: the box at rest of the triangles in no part, then of each part's.
    std::vector<Eigen::AlignedBox3d> part_boxes;
    double max_reflectance = 0.0;  ///< of its materials: bounds its echo
};

/// What one beam's cone holds (one per thread, reused).
struct TargetsInCone {
    std::vector<raytrace::ObjectBounds> objects;  ///< every object near the cone, at the beam's time
    bool media = false;
    std::optional<FootprintRect> outline;  ///< of every small or moving object met, together
    int count = 0;
    double brightest_j = 0.0;   ///< the largest echo any of them could send back
    std::uint32_t lone_id = 0;  ///< the last one met: with one, that one
    /// Those with a mesh, which seeds can be taken on, and their seed candidates.
    std::vector<std::pair<const raytrace::ObjectBounds*, const TargetSeeds*>> with_seeds;
};

class BeamCone {
public:
    /// Seed candidates of each mesh object among `objects`.
    BeamCone(const FootprintContext& context, const std::vector<scene::SceneObject>& objects);

    /// Finds the targets and media the cone of `aim` touches. Objects subtending at least
    /// context.small_object_rad that do not move are left to the probes.
    void find(const BeamAim& aim, TargetsInCone& out) const;
    /// Traces the seeds of the targets found (a ray at each of their seed candidates nearest the
    /// axis, inside the truncation) and appends them to `witnesses`, their hits in `hits`.
    void add_seeds(const BeamAim& aim, const TargetsInCone& targets, std::vector<Probe>& seeds, std::vector<ProbeHit>& hits,
                   std::vector<const Probe*>& witnesses, BeamEchoes& out) const;

private:
    /// The outline of object `b` (its bounding sphere passed the cone test) in the footprint, or
    /// nothing where it lies outside.
    std::optional<FootprintRect> outline_of(const raytrace::ObjectBounds& b, bool inside, const BeamAim& aim) const;
    /// Appends the footprint offsets of the seed candidates of target `b` nearest the beam's axis
    /// (placed where its animation has them at the beam's time), those inside the truncation.
    void seed_offsets(const raytrace::ObjectBounds& b, const TargetSeeds& seeds, const BeamAim& aim,
                      std::vector<Eigen::Vector2d>& out) const;

    const FootprintContext& context_;
    std::unordered_map<std::uint32_t, TargetSeeds> target_shapes_;  ///< by object id
};

}  // namespace ladarsim::sensor_model
