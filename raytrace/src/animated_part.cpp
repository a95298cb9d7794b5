#include "animated_part.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/LU>

#include "ladarsim/scene/animation.h"

namespace ladarsim::raytrace {
namespace {

std::atomic<std::size_t> parts_made{0};

// Consecutive samples of a window's placements may turn a box edge by at most this much: the part
// then turns by under 45 deg between them (of two orthogonal edges, one turns by at least half the
// rotation's versine), its corners' paths are at most 3 % longer than their chords, and every
// point of a path lies within about half a chord of the nearer sample.
constexpr double kSampleTurnRad = 30.0 * std::numbers::pi / 180.0;
constexpr int kFirstSamples = 9;
constexpr int kMostSamples = 4097;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace

Matrix34 relative_from_model(const scene::SceneObject& object, const Eigen::Vector3d& origin_world, double time_s) {
    Eigen::Isometry3d pose = object.trajectory.at(time_s).world_from_object();
    pose.translation() -= origin_world;
    const Eigen::Affine3d m = pose * Eigen::Scaling(object.scale);
    return m.matrix().topRows<3>();
}

AnimatedObject::AnimatedObject(const scene::SceneObject& object, const Eigen::Vector3d& origin_world)
    : object_(&object), motions_(*object.model, object.animation), origin_world_(origin_world) {}

void AnimatedObject::pose(double time_s, Posed& out) const {
    out.relative_from_model = relative_from_model(*object_, origin_world_, time_s);
    motions_.at(time_s, out.motions);
}

Matrix34 AnimatedObject::part_of(const Posed& posed, int part) {
    if (part < 0) return posed.relative_from_model;
    return posed.relative_from_model * posed.motions[static_cast<std::size_t>(part)].matrix();
}

Matrix34 AnimatedObject::placement(int part, double time_s) const {
    const Matrix34 m = relative_from_model(*object_, origin_world_, time_s);
    return part < 0 ? m : Matrix34(m * motions_.at(static_cast<std::size_t>(part), time_s).matrix());
}

AnimatedPart& AnimatedObject::add_part(int part, RTCScene bvh, const std::vector<std::uint32_t>& triangles) {
    return parts_.emplace_back(*this, part, bvh, object_->model->mesh, triangles);
}

void AnimatedObject::set_window(double begin_s, double length_s) {
    window_begin_s_ = begin_s;
    window_length_s_ = length_s;
    // Evenly spaced times, twice as many until every part turns little enough between them; each
    // doubling keeps the times it had.
    std::vector<Posed> posed(kFirstSamples);
    for (int k = 0; k < kFirstSamples; ++k) pose(begin_s + length_s * k / (kFirstSamples - 1), posed[static_cast<std::size_t>(k)]);
    std::vector<std::vector<Matrix34>> placed(parts_.size());
    for (;;) {
        bool fine = true;
        for (std::size_t p = 0; p < parts_.size(); ++p) {
            placed[p].clear();
            for (const Posed& s : posed) placed[p].push_back(part_of(s, parts_[p].part_));
            fine = fine && parts_[p].largest_turn_rad(placed[p]) <= kSampleTurnRad;
        }
        if (fine || static_cast<int>(posed.size()) >= kMostSamples) break;
        const std::size_t n = 2 * posed.size() - 1;
        std::vector<Posed> finer(n);
        for (std::size_t k = 0; k < n; ++k) {
            if (k % 2 == 0) finer[k] = std::move(posed[k / 2]);
            else pose(begin_s + length_s * static_cast<double>(k) / static_cast<double>(n - 1), finer[k]);
        }
        posed = std::move(finer);
    }
    for (std::size_t p = 0; p < parts_.size(); ++p) parts_[p].bound(placed[p]);
}

AnimatedPart::AnimatedPart(const AnimatedObject& object, int part, RTCScene bvh, const scene::TriangleMesh& mesh,
                           const std::vector<std::uint32_t>& triangles)
    : object_(&object), part_(part), bvh_(bvh), box_model_(scene::bounds_of(mesh, triangles)), serial_(parts_made++) {}

Geometry AnimatedPart::make_geometry(RTCDevice device) const {
    Geometry g(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER));
    rtcSetGeometryUserPrimitiveCount(g.get(), 1);
    rtcSetGeometryUserData(g.get(), const_cast<AnimatedPart*>(this));
    rtcSetGeometryBoundsFunction(g.get(), &AnimatedPart::bounds, nullptr);
    rtcSetGeometryIntersectFunction(g.get(), &AnimatedPart::intersect);
    return g;
}

double AnimatedPart::largest_turn_rad(const std::vector<Matrix34>& samples) const {
    double turn = 0.0;
    for (std::size_t k = 0; k + 1 < samples.size(); ++k)
        for (int axis = 0; axis < 3; ++axis) {
            const Eigen::Vector3d edge = samples[k].col(axis) * box_model_.sizes()[axis];
            const Eigen::Vector3d next = samples[k + 1].col(axis) * box_model_.sizes()[axis];
            if (edge.norm() > 0.0 && next.norm() > 0.0) turn = std::max(turn, angle_between(edge, next));
        }
    return turn;
}

void AnimatedPart::bound(const std::vector<Matrix34>& samples) {
    Eigen::AlignedBox3d box;
    double chord = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k)
        for (int c = 0; c < 8; ++c) {
            const Eigen::Vector4d corner = box_model_.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).homogeneous();
            const Eigen::Vector3d p = samples[k] * corner;
            box.extend(p);
            if (k > 0) chord = std::max(chord, (p - samples[k - 1] * corner).norm());
        }
    // Grown by a chord (twice the reach between samples) and a hair for the float box.
    const double pad = chord + 1e-6 * (1.0 + std::max(box.max().cwiseAbs().maxCoeff(), box.min().cwiseAbs().maxCoeff()));
    window_box_ = RTCBounds{static_cast<float>(box.min().x() - pad), static_cast<float>(box.min().y() - pad),
                            static_cast<float>(box.min().z() - pad), 0.0f,
                            static_cast<float>(box.max().x() + pad), static_cast<float>(box.max().y() + pad),
                            static_cast<float>(box.max().z() + pad), 0.0f};
}

const AnimatedPart::Placement& AnimatedPart::placement(float u) const {
    // A slot per part, grown on first use.
    thread_local std::vector<Placement> cache;
    if (cache.size() <= serial_) cache.resize(serial_ + 1);
    Placement& p = cache[serial_];
    const double time_s = object_->time_at(u);
    if (!(p.time_s == time_s)) {
        p.time_s = time_s;
        p.relative_from_model = object_->placement(part_, time_s);
        p.model_from_relative_linear = p.relative_from_model.leftCols<3>().inverse();
    }
    return p;
}

const Matrix34& AnimatedPart::relative_from_model_at(float u) const { return placement(u).relative_from_model; }

void AnimatedPart::bounds(const RTCBoundsFunctionArguments* args) {
    *args->bounds_o = static_cast<const AnimatedPart*>(args->geometryUserPtr)->window_box_;
}

void AnimatedPart::intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* self = static_cast<const AnimatedPart*>(args->geometryUserPtr);
    const unsigned n = args->N;
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] == 0) continue;
        const Placement& p = self->placement(RTCRayN_time(rays, n, i));
        const Eigen::Vector3d o(RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i));
        const Eigen::Vector3d d(RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i));
        // The direction is not renormalised, so distances along the ray are the same in both frames.
        const Eigen::Vector3d o_model = p.model_from_relative_linear * (o - p.relative_from_model.col(3));
        const Eigen::Vector3d d_model = p.model_from_relative_linear * d;
        RTCRayHit rh{};
        rh.ray.org_x = static_cast<float>(o_model.x());
        rh.ray.org_y = static_cast<float>(o_model.y());
        rh.ray.org_z = static_cast<float>(o_model.z());
        rh.ray.dir_x = static_cast<float>(d_model.x());
        rh.ray.dir_y = static_cast<float>(d_model.y());
        rh.ray.dir_z = static_cast<float>(d_model.z());
        rh.ray.tnear = RTCRayN_tnear(rays, n, i);
        rh.ray.tfar = RTCRayN_tfar(rays, n, i);
        rh.ray.mask = RTCRayN_mask(rays, n, i);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcIntersect1(self->bvh_, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const Eigen::Vector3d normal =
            p.model_from_relative_linear.transpose() * Eigen::Vector3d(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        RTCRayN_tfar(rays, n, i) = rh.ray.tfar;
        RTCHitN_Ng_x(hits, n, i) = static_cast<float>(normal.x());
        RTCHitN_Ng_y(hits, n, i) = static_cast<float>(normal.y());
        RTCHitN_Ng_z(hits, n, i) = static_cast<float>(normal.z());
        RTCHitN_u(hits, n, i) = rh.hit.u;
        RTCHitN_v(hits, n, i) = rh.hit.v;
        RTCHitN_primID(hits, n, i) = rh.hit.primID;
        RTCHitN_geomID(hits, n, i) = rh.hit.geomID;
        // As Embree reports a hit inside an instance: the instance is this geometry.
        RTCHitN_instID(hits, n, i, 0) = args->geomID;
    }
}

}  // namespace ladarsim::raytrace
