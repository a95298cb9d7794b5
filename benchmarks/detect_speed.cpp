// Algorithm 1's cost per frame, and the tracker of every target's: a 3,000-point frame (the paper's
// raster) against background maps of 100 k and 1 M points. Prints ms per frame and the ratio to the
// sensor's 50 ms frame period.
#include <chrono>
#include <cstdio>
#include <random>

#include "ladarsim/detect/multi_target.h"
#include "ladarsim/detect/tracker.h"

using namespace ladarsim::detect;
using Clock = std::chrono::steady_clock;

namespace {

/// The paper's raster: 150 x 20 beams over 0.5 x 0.5 deg, 0.62 mrad beams.
const ladarsim::SensorGeometry kPaperSensor{
    .beams_az = 150, .beams_el = 20, .field_az_deg = 0.5, .field_el_deg = 0.5, .divergence_mrad = 0.62};

/// A terrain-like map: points on a gently rolling surface 1.5-2.5 km out, across the field.
Points map_of(std::size_t n, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Points p;
    for (std::size_t i = 0; i < n; ++i) {
        const float y = -40.0f + 80.0f * u(rng), z = 60.0f + 40.0f * u(rng);
        p.emplace_back(2000.0f + 500.0f * u(rng) * 0.01f + 0.002f * y * y, y, z);
    }
    return p;
}

}  // namespace

int main() {
    std::mt19937 rng(1);
    std::normal_distribution<float> jitter(0.0f, 0.02f);
    for (std::size_t map_points : {std::size_t{100'000}, std::size_t{1'000'000}}) {
        const Points map = map_of(map_points, rng);
        // Frames: 2,990 points drawn from the map (static background, 2 cm range noise) plus a 10-point drone.
        std::vector<Points> frames;
        for (int f = 0; f < 50; ++f) {
            Points frame;
            std::uniform_int_distribution<std::size_t> pick(0, map.size() - 1);
            for (int i = 0; i < 2990; ++i) frame.push_back(map[pick(rng)] + Eigen::Vector3f(jitter(rng), 0.0f, 0.0f));
            for (int i = 0; i < 10; ++i) frame.emplace_back(600.0f - 0.75f * f, 0.035f * i, 20.0f + 0.26f * (i % 2));
            frames.push_back(std::move(frame));
        }
        for (Method method : {Method::rbnn, Method::vrbnn, Method::kalman}) {
            DetectorConfig config;
            config.method = method;
            config.rbnn_radius_m = 0.3;
            config.lambda = 180.0;
            const auto built = Clock::now();
            TargetTracker tracker(config, kPaperSensor, map);
            const double build_ms = std::chrono::duration<double, std::milli>(Clock::now() - built).count();
            const auto start = Clock::now();
            int found = 0;
            for (std::size_t f = 0; f < frames.size(); ++f) found += tracker.process(f, 0.05 * f, frames[f]).found;
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count() / frames.size();
            std::printf("map %8zu points, %-6s: map voxels %7.1f ms once, %.3f ms per 3000-point frame (%.1f%% of the 50 ms frame period), target found in %d/%zu frames\n",
                        map_points, to_string(method).c_str(), build_ms, ms, 100.0 * ms / 50.0, found, frames.size());
        }
        DetectorConfig config;
        config.lambda = 180.0;
        MultiTargetTracker every(config, kPaperSensor, map);
        const auto start = Clock::now();
        std::size_t tracked = 0;
        for (std::size_t f = 0; f < frames.size(); ++f) tracked += every.process(0.05 * f, frames[f]).size();
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count() / frames.size();
        std::printf("map %8zu points, every target: %.3f ms per 3000-point frame (%.1f%% of the 50 ms frame period), %zu track-frames\n",
                    map_points, ms, 100.0 * ms / 50.0, tracked);
    }
    return 0;
}
