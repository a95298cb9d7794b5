// The supervised run behind EAO (VOT's protocol) on hand-made sequences: a tracker is scored on
// what it finds, not on the ground-truth box it was (re-)initialised with.
#include <catch2/catch.hpp>

#include "ladarsim/detect/expected_overlap.h"
#include "ladarsim/detect/sequence.h"

using namespace ladarsim;

namespace {

/// A drone (0.3 x 0.3 x 0.1 m) hovering still 600 m ahead for `frames` frames at 20 Hz, seen by
/// the paper's raster. `visible`: each frame holds a small cloud of returns on it; otherwise the
/// frames hold only a return 200 m off to the side.
detect::Sequence hovering_drone(int frames, bool visible) {
    detect::Sequence s;
    s.sensor = {150, 20, 0.5, 0.5, 0.62};
    const Eigen::Vector3d centre(600.0, 0.0, 5.0);
    for (int i = 0; i < frames; ++i) {
        s.frame_index.push_back(static_cast<std::uint64_t>(i));
        s.time_s.push_back(i / 20.0);
        detect::Points points;
        if (visible) {
            for (int a = -2; a <= 2; ++a)
                for (int b = -1; b <= 1; ++b)
                    points.push_back((centre + Eigen::Vector3d(0.03 * b, 0.06 * a, 0.04 * b)).cast<float>());
        } else {
            points.push_back(Eigen::Vector3f(600.0f, 200.0f, 5.0f));
        }
        s.frames.push_back(points);
        s.boresight.push_back(centre.normalized());
        FrameGroundTruth truth;
        truth.index = static_cast<std::uint64_t>(i);
        GroundTruthObject drone;
        drone.object_id = 1;
        drone.object_class = "drone";
        drone.box_sensor.centre = centre;
        drone.box_sensor.size = {0.3, 0.3, 0.1};
        truth.objects.push_back(drone);
        s.truth.push_back(truth);
    }
    return s;
}

double eao_of(const detect::SupervisedRun& run, int frames) {
    return detect::expected_average_overlap(detect::fragments_of(run.iou, run.initialised), 2, frames);
}

}  // namespace

TEST_CASE("a tracker that never detects its target scores no overlap and fails, however still the target", "[detect][eao]") {
    const detect::Sequence s = hovering_drone(40, false);
    detect::DetectorConfig config;
    config.lambda = 180.0;
    // Re-initialised on the truth, it can only replay that box: nothing it found. So for both
    // boxes, in 3-D and in bird's-eye view.
    for (const auto& [name, run] : detect::supervised_runs(s, config, 1)) {
        INFO(name);
        CHECK(run.failures >= 6);  // a failure every 6 frames: fail, skip 5, re-initialise
        CHECK(eao_of(run, 40) <= 0.01);
    }
}

TEST_CASE("a tracker that detects a hovering target keeps its overlap and does not fail", "[detect][eao]") {
    const detect::Sequence s = hovering_drone(40, true);
    detect::DetectorConfig config;
    config.lambda = 180.0;
    const detect::SupervisedRun run = detect::supervised_run(s, config, 1);
    CHECK(run.failures == 0);
    // Every frame's box is the cluster's, 0.06 x 0.24 x 0.08 m inside the 0.3 x 0.3 x 0.1 m truth:
    // IoU = 0.001152 / 0.009 = 0.128 in every frame, and so EAO.
    CHECK(eao_of(run, 40) == Approx(0.06 * 0.24 * 0.08 / (0.3 * 0.3 * 0.1)).epsilon(1e-3));
}

TEST_CASE("the sensor-aware box of a hovering target: the prior's size at the returns' centre", "[detect][eao]") {
    const detect::Sequence s = hovering_drone(40, true);
    detect::DetectorConfig config;
    config.lambda = 180.0;
    const detect::SupervisedRuns runs = detect::supervised_runs(s, config, 1);
    // The cluster (0.06 x 0.24 x 0.08 m, centred on the drone) less a footprint's spread
    // (1.5 x 0.62 mrad x 600 m = 0.56 m across the line of sight) is smaller than the prior
    // 0.3 x 0.3 x 0.06 m on every axis: the box is the prior's, at the drone's centre. Against the
    // 0.3 x 0.3 x 0.1 m truth: 0.6 in 3-D, 1 in bird's-eye view, in every frame.
    CHECK(runs.at("sensor_3d").failures == 0);
    CHECK(eao_of(runs.at("sensor_3d"), 40) == Approx(0.06 / 0.1).epsilon(1e-6));
    CHECK(eao_of(runs.at("sensor_bev"), 40) == Approx(1.0).epsilon(1e-6));
    // The box around the points, seen from above: 0.06 x 0.24 inside 0.3 x 0.3.
    CHECK(eao_of(runs.at("points_bev"), 40) == Approx(0.06 * 0.24 / (0.3 * 0.3)).epsilon(1e-3));
}
