#pragma once
// How footprints are integrated: what the integrator takes of a scenario (its render settings and
// where the sensor stands), so that it never reads the scenario itself.
#include <cstdint>

#include <Eigen/Core>

namespace ladarsim::sensor_model {

struct FootprintSettings {
    Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< where every ray leaves: the sensor's position
    /// Stratified sub-rays per beam (the brute-force reference); 0: adaptive (docs/sensor.md).
    int samples = 0;
    /// With samples > 0: lines of a dense scanline over a recorded map (its converged reference),
    /// the samples spread over them as rays for other objects; 0: the sub-rays there too.
    int map_lines = 0;
    double tolerance = 0.05;   ///< of a return's energy, adaptive footprints' accuracy
    double truncation = 1.5;   ///< sub-rays lie within this many 1/e^2 radii
    bool jitter = true;        ///< sub-rays jittered within their cells
    std::uint64_t seed = 1;    ///< keys the jitter's and the media's random draws
};

}  // namespace ladarsim::sensor_model
