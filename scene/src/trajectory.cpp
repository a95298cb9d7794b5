#include "ladarsim/scene/trajectory.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include "ladarsim/core/units.h"

namespace ladarsim::scene {

namespace {

/// Orientation whose model +X (forward) points along `direction`, with no roll.
Eigen::Quaterniond heading_of(const Eigen::Vector3d& direction) {
    const double horizontal = std::hypot(direction.x(), direction.y());
    if (horizontal == 0.0 && direction.z() == 0.0) return Eigen::Quaterniond::Identity();
    const double yaw = std::atan2(direction.y(), direction.x());
    const double pitch = -std::atan2(direction.z(), horizontal);  // rotating +X about +Y by p gives z = -sin p
    return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
}

/// Horizontal unit vector to the left of `velocity` (falls back to +Y for vertical motion).
Eigen::Vector3d lateral_of(const Eigen::Vector3d& velocity) {
    const Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(velocity);
    return left.norm() > 0.0 ? left.normalized() : Eigen::Vector3d::UnitY();
}

Eigen::Vector3d catmull_rom(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                            const Eigen::Vector3d& p3, double u) {
    const double u2 = u * u, u3 = u2 * u;
    return 0.5 * ((2.0 * p1) + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 +
                  (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
}

struct Evaluate {
    double t;

    Pose operator()(const Trajectory::Fixed& f) const { return f.pose; }

    Pose operator()(const Trajectory::Keyed& k) const {
        const auto& keys = k.keys;
        if (t <= keys.front().time_s) return keys.front().pose;
        if (t >= keys.back().time_s) return keys.back().pose;
        const auto upper = std::upper_bound(keys.begin(), keys.end(), t,
                                            [](double time, const Keyframe& key) { return time < key.time_s; });
        const std::size_t i = static_cast<std::size_t>(upper - keys.begin()) - 1;
        const Keyframe& a = keys[i];
        const Keyframe& b = keys[i + 1];
        const double u = (t - a.time_s) / (b.time_s - a.time_s);
        Pose p;
        p.orientation = a.pose.orientation.slerp(u, b.pose.orientation);
        if (k.interpolation == Interpolation::linear) {
            p.position = (1.0 - u) * a.pose.position + u * b.pose.position;
        } else {
            // Uniform Catmull-Rom; end segments reuse the end key as the missing neighbour.
            const Eigen::Vector3d& p0 = keys[i == 0 ? 0 : i - 1].pose.position;
            const Eigen::Vector3d& p3 = keys[std::min(i + 2, keys.size() - 1)].pose.position;
            p.position = catmull_rom(p0, a.pose.position, b.pose.position, p3, u);
        }
        return p;
    }

    Pose operator()(const Trajectory::Straight& s) const {
        return Pose{s.start + s.velocity_mps * t, heading_of(s.velocity_mps)};
    }

    Pose operator()(const Trajectory::Winding& w) const {
        const double omega = 2.0 * std::numbers::pi / w.period_s;
        const Eigen::Vector3d lateral = lateral_of(w.velocity_mps);
        const Eigen::Vector3d position =
            w.start + w.velocity_mps * t + w.amplitude_m * std::sin(omega * t) * lateral;
        const Eigen::Vector3d velocity = w.velocity_mps + w.amplitude_m * omega * std::cos(omega * t) * lateral;
        return Pose{position, heading_of(velocity)};
    }

    Pose operator()(const Trajectory::Hover& h) const {
        const double phase = 2.0 * std::numbers::pi * t / h.period_s;
        return Pose{h.centre + h.radius_m * Eigen::Vector3d(std::cos(phase), std::sin(phase), 0.0),
                    Eigen::Quaterniond::Identity()};
    }
};

}  // namespace

Eigen::Quaterniond orientation_from_ypr_deg(double yaw_deg, double pitch_deg, double roll_deg) {
    // A positive rotation about +y tips +x down, so nose-up pitch is a negative angle about +y.
    return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(-pitch_deg * kDeg, Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()));
}

Eigen::Isometry3d Pose::world_from_object() const {
    Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
    m.translate(position);
    m.rotate(orientation.normalized());
    return m;
}

Trajectory Trajectory::fixed(const Pose& pose) { return Trajectory(Fixed{pose}); }

Trajectory Trajectory::keyframes(std::vector<Keyframe> keys, Interpolation interpolation) {
    if (keys.empty()) throw std::invalid_argument("a keyframe trajectory needs at least one keyframe");
    for (std::size_t i = 1; i < keys.size(); ++i) {
        if (!(keys[i].time_s > keys[i - 1].time_s)) {
            throw std::invalid_argument("keyframe times must increase strictly");
        }
    }
    return Trajectory(Keyed{std::move(keys), interpolation});
}

Trajectory Trajectory::straight(const Eigen::Vector3d& start, const Eigen::Vector3d& velocity_mps) {
    return Trajectory(Straight{start, velocity_mps});
}

Trajectory Trajectory::winding(const Eigen::Vector3d& start, const Eigen::Vector3d& velocity_mps,
                               double amplitude_m, double period_s) {
    if (!(period_s > 0.0)) throw std::invalid_argument("a winding trajectory needs a positive period");
    return Trajectory(Winding{start, velocity_mps, amplitude_m, period_s});
}

Trajectory Trajectory::hover(const Eigen::Vector3d& centre, double radius_m, double period_s) {
    if (!(period_s > 0.0)) throw std::invalid_argument("a hover trajectory needs a positive period");
    return Trajectory(Hover{centre, radius_m, period_s});
}

Pose Trajectory::at(double time_s) const { return std::visit(Evaluate{time_s}, path_); }

bool Trajectory::is_static() const {
    if (std::holds_alternative<Fixed>(path_)) return true;
    if (const auto* k = std::get_if<Keyed>(&path_)) return k->keys.size() == 1;
    if (const auto* s = std::get_if<Straight>(&path_)) return s->velocity_mps.isZero();
    if (const auto* h = std::get_if<Hover>(&path_)) return h->radius_m == 0.0;
    return false;
}

}  // namespace ladarsim::scene
