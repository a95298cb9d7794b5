#include "bench_frames.h"

#include <cmath>
#include <fstream>
#include <map>
#include <ctime>
#include <unistd.h>

#include "ladarsim/sensor_model/render/frame_renderer.h"

namespace ladarsim::bench {

Rendering render_frames(const sensor_model::Scenario& scenario, const std::vector<std::uint64_t>& indices) {
    sensor_model::FrameRenderer renderer(scenario);
    Rendering r;
    // The gimbal replays from frame 0: settle it before the clock starts.
    if (!indices.empty()) renderer.gimbal_pointing(indices.back());
    const auto start = Clock::now();
    for (const std::uint64_t i : indices) {
        r.frames.push_back(renderer.render(i));
        r.rays += renderer.rays_last_frame();
        r.beams += static_cast<std::uint64_t>(renderer.raster().beam_count());
    }
    r.seconds = seconds_since(start);
    return r;
}

ObjectError compare(const Rendering& r, const Rendering& reference, std::uint32_t object_id) {
    struct Seen {
        std::uint64_t returns = 0;
        double energy = 0.0;
        std::map<std::uint64_t, double> first_range;  ///< by (frame, row, column)
    };
    auto tally = [&](const Rendering& x) {
        Seen s;
        for (std::size_t f = 0; f < x.frames.size(); ++f) {
            for (const Return& ret : x.frames[f].returns) {
                if (ret.object_id != object_id) continue;
                ++s.returns;
                s.energy += ret.intensity;
                const std::uint64_t key = (f << 32) | (std::uint64_t{ret.row} << 16) | ret.column;
                s.first_range.emplace(key, ret.range_m);
            }
        }
        return s;
    };
    const Seen a = tally(r), b = tally(reference);
    ObjectError e;
    e.returns = a.returns;
    e.reference_returns = b.returns;
    if (b.returns > 0) {
        e.count_error_pct = 100.0 * (double(a.returns) - double(b.returns)) / double(b.returns);
        e.energy_error_pct = 100.0 * (a.energy - b.energy) / b.energy;
    }
    double sum = 0.0;
    int n = 0;
    for (const auto& [key, range] : a.first_range) {
        const auto it = b.first_range.find(key);
        if (it == b.first_range.end()) continue;
        sum += std::abs(range - it->second);
        ++n;
    }
    e.range_error_mm = n ? 1e3 * sum / n : 0.0;
    return e;
}

sensor_model::Scenario with_footprint(sensor_model::Scenario s, int samples, double tolerance) {
    s.render.footprint_samples = samples;
    s.render.footprint_tolerance = tolerance;
    return s;
}

sensor_model::Scenario with_map_reference(sensor_model::Scenario s, int samples, int lines) {
    s = with_footprint(std::move(s), samples, 0.0);
    s.render.footprint_map_lines = lines;
    return s;
}

double thread_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::uint64_t resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    std::uint64_t size = 0, resident = 0;
    statm >> size >> resident;
    return resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace ladarsim::bench
