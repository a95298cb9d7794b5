#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/mesh.h"
#include "ladarsim/scene/object_class.h"
#include "ladarsim/scene/trajectory.h"

namespace ladarsim::scene {

/// Object id reserved for the recorded background map; scenario objects have ids >= 1.
inline constexpr std::uint32_t kBackgroundObjectId = 0;

struct SceneObject {
    std::uint32_t id = 1;
    ObjectClass object_class = ObjectClass::drone;
    std::string name;
    /// Shared so that many objects can instance one mesh.
    std::shared_ptr<const Model> model;
    /// Uniform scale applied in the model frame before the pose: world = pose * (scale * p).
    double scale = 1.0;
    Trajectory trajectory = Trajectory::fixed(Pose{});
    /// Which of the model's animations play (all by default), on top of the trajectory.
    AnimationChoice animation;
};

/// A recorded point cloud traced as oriented discs.
struct BackgroundMap {
    std::string source;
    std::vector<Eigen::Vector3d> points_world;
    std::vector<Eigen::Vector3f> normals;  ///< unit, from a local plane fit
    std::vector<float> radii_m;            ///< disc radius from the local point spacing
    std::vector<float> reflectance;        ///< per point, 0..1
};

struct Scene {
    std::vector<SceneObject> objects;
    std::optional<BackgroundMap> background;
};

}  // namespace ladarsim::scene
