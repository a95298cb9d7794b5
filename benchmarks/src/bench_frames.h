#pragma once
// What the benchmarks share: rendering a list of frames in memory, timed, and comparing the
// returns of two renderings of the same frames.
#include <chrono>
#include <cstdint>
#include <vector>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// CPU time of the calling thread (s): work done, whatever else the machine runs.
double thread_cpu_seconds();

struct Rendering {
    std::vector<Frame> frames;
    double seconds = 0.0;
    std::uint64_t beams = 0;
    std::uint64_t rays = 0;
    double beams_per_second() const { return beams / seconds; }
    double rays_per_beam() const { return double(rays) / double(beams); }
};

/// Renders `indices` of a scenario (frames kept in memory, nothing written), timing the frames
/// only (not building the scene).
Rendering render_frames(const sensor_model::Scenario& scenario, const std::vector<std::uint64_t>& indices);

/// One object's returns in a rendering, against a reference rendering of the same frames.
struct ObjectError {
    std::uint64_t returns = 0, reference_returns = 0;
    double count_error_pct = 0.0;
    double energy_error_pct = 0.0;  ///< summed intensity of its returns
    double range_error_mm = 0.0;    ///< mean |range difference| over beams where both see it
};

ObjectError compare(const Rendering& r, const Rendering& reference, std::uint32_t object_id);

/// The scenario with another footprint integration: `samples` > 0 fixed, else adaptive at `tolerance`.
sensor_model::Scenario with_footprint(sensor_model::Scenario s, int samples, double tolerance);
/// Lines across a footprint of the recorded map's converged reference: against twice as many its
/// first returns differ by 1.6 mm mean (median 0.02 mm; 256 lines were 2.8 mm from 512) over
/// dataset 2 over Autzen (`ladarsim bench`, hard cases), the beams near the threshold flipping.
inline constexpr int kMapReferenceLines = 512;
/// The converged reference over a recorded map: a scanline of `lines` across each footprint over
/// the map's discs, `samples` rays a beam spread over its lines for other objects.
sensor_model::Scenario with_map_reference(sensor_model::Scenario s, int samples, int lines);

/// Memory the process holds now (resident set, bytes).
std::uint64_t resident_bytes();

}  // namespace ladarsim::bench
