// MultiTargetTracker on synthetic frames: targets cross without trading ids, a one-frame blip is
// never confirmed, a track outlives a short gap.
#include <catch2/catch.hpp>

#include <map>

#include "ladarsim/detect/multi_target.h"

using namespace ladarsim;

namespace {

/// A compact cloud of 15 returns about `centre` (0.06 m apart: a drone's returns at 600 m).
void add_target(detect::Points& points, const Eigen::Vector3d& centre) {
    for (int a = -2; a <= 2; ++a)
        for (int b = -1; b <= 1; ++b) points.push_back((centre + Eigen::Vector3d(0.03 * b, 0.06 * a, 0.04 * b)).cast<float>());
}

Eigen::Vector3d a_at(int frame) { return {600.0, -2.0 + 0.2 * frame, 5.0}; }
Eigen::Vector3d b_at(int frame) { return {600.0, 2.0 - 0.2 * frame, 5.8}; }

}  // namespace

TEST_CASE("two targets crossing keep their tracks, and a one-frame blip is never confirmed", "[detect][multi_target]") {
    const SensorGeometry sensor{150, 20, 0.5, 0.5, 0.62};
    detect::DetectorConfig config;
    detect::MultiTargetTracker tracker(config, sensor, {});
    std::map<char, std::uint32_t> id;
    for (int frame = 0; frame < 21; ++frame) {
        detect::Points points;
        add_target(points, a_at(frame));
        add_target(points, b_at(frame));
        if (frame == 7) add_target(points, {600.0, 0.0, 9.0});  // a blip, gone the next frame
        const auto tracks = tracker.process(frame * 0.05, points);
        INFO("frame " << frame);
        if (frame == 0) {
            CHECK(tracks.empty());  // a track is confirmed by its second cluster
            continue;
        }
        REQUIRE(tracks.size() == 2);
        for (const auto& t : tracks) {
            CHECK_FALSE(t.predicted);
            const char which = (t.box.centre - a_at(frame)).norm() < (t.box.centre - b_at(frame)).norm() ? 'a' : 'b';
            CHECK((t.box.centre - (which == 'a' ? a_at(frame) : b_at(frame))).norm() < 0.05);
            if (!id.count(which)) id[which] = t.track;
            CHECK(t.track == id[which]);  // crossing at frame 10, 0.8 m apart: no swap
        }
    }
    CHECK(id['a'] != id['b']);
}

TEST_CASE("a confirmed track outlives a short gap as a prediction, and ends after a long one", "[detect][multi_target]") {
    const SensorGeometry sensor{150, 20, 0.5, 0.5, 0.62};
    detect::MultiTargetTracker tracker(detect::DetectorConfig{}, sensor, {});
    std::uint32_t first = 0;
    for (int frame = 0; frame < 20; ++frame) {
        detect::Points points;
        const bool seen = frame < 5 || (frame >= 8 && frame < 10);  // unseen in 5-7, and from 10 on
        if (seen) add_target(points, a_at(frame));
        const auto tracks = tracker.process(frame * 0.05, points);
        INFO("frame " << frame);
        if (frame == 0) continue;
        if (frame <= 10 + detect::MultiTargetTracker::kMaxMisses - 1) {
            REQUIRE(tracks.size() == 1);
            if (!first) first = tracks.front().track;
            CHECK(tracks.front().track == first);
            CHECK(tracks.front().predicted == !seen);
            // Predicted along its velocity (0.2 m a frame along y).
            CHECK((tracks.front().box.centre - a_at(frame)).norm() < 0.05);
        } else {
            CHECK(tracks.empty());
        }
    }
}
