#pragma once
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ladarsim::scene {

/// Placement of an object: world_from_object = translation(position) * orientation.
struct Pose {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();

    Eigen::Isometry3d world_from_object() const;
};

/// Orientation from aircraft angles in degrees: yaw about +z (positive turns +x towards +y),
/// pitch positive nose up, roll about +x; applied as yaw, then pitch, then roll (intrinsic).
Eigen::Quaterniond orientation_from_ypr_deg(double yaw_deg, double pitch_deg, double roll_deg);

struct Keyframe {
    double time_s = 0.0;
    Pose pose;
};

enum class Interpolation { linear, smooth };

/// Where an object is at any time. Evaluated at each pulse's own emission time.
class Trajectory {
public:
    /// Never moves.
    static Trajectory fixed(const Pose& pose);
    /// Piecewise path through keyframes (sorted by time, at least one); clamps outside the range.
    /// `smooth` is a uniform Catmull-Rom spline on positions (end keys repeated as the missing
    /// neighbours) and slerp on orientations.
    static Trajectory keyframes(std::vector<Keyframe> keys, Interpolation interpolation);
    /// Constant velocity from `start` at time 0, nose along the velocity.
    static Trajectory straight(const Eigen::Vector3d& start, const Eigen::Vector3d& velocity_mps);
    /// Straight mean path with a horizontal sinusoidal weave perpendicular to it.
    static Trajectory winding(const Eigen::Vector3d& start, const Eigen::Vector3d& velocity_mps,
                              double amplitude_m, double period_s);
    /// Hovering about `centre` with a slow circular drift of `radius_m` per `period_s`.
    static Trajectory hover(const Eigen::Vector3d& centre, double radius_m, double period_s);

    Pose at(double time_s) const;
    /// True when at() returns the same pose for every time (no motion blur needed).
    bool is_static() const;

    struct Fixed { Pose pose; };
    struct Keyed { std::vector<Keyframe> keys; Interpolation interpolation; };
    struct Straight { Eigen::Vector3d start, velocity_mps; };
    struct Winding { Eigen::Vector3d start, velocity_mps; double amplitude_m, period_s; };
    struct Hover { Eigen::Vector3d centre; double radius_m, period_s; };

private:
    using Path = std::variant<Fixed, Keyed, Straight, Winding, Hover>;
    explicit Trajectory(Path path) : path_(std::move(path)) {}
    Path path_;
};

}  // namespace ladarsim::scene
