// Where do two renderings of the same frames over a recorded map disagree, beam by beam? Prints
// the beams whose first returns on the map differ most (as `ladarsim bench` judges the map: its
// returns alone), with every return of each, to tell what the footprint holds there (a weak near
// return on one side of the threshold, another object in front, a grazing edge).
//
// usage: map_reference_diff SCENARIO.json LINES_A SAMPLES_A LINES_B SAMPLES_B [FRAMES] [SHOWN]
//   LINES 0 and SAMPLES 0: the default adaptive integration; LINES 0, SAMPLES > 0: sub-rays.
//   FRAMES N > 0: N frames spread over the scenario's (the bench's choice); -K: frame K alone.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "bench_frames.h"
#include "ladarsim/sensor_model/render/scenario.h"

using namespace ladarsim;

namespace {

struct Beam {
    std::vector<Return> returns;  ///< the map's, in range order as the frame lists them
    std::vector<Return> all;      ///< every object's
};

std::map<std::uint64_t, Beam> by_beam(const bench::Rendering& r) {
    std::map<std::uint64_t, Beam> beams;
    for (std::size_t f = 0; f < r.frames.size(); ++f)
        for (const Return& ret : r.frames[f].returns)
            if (ret.object_id == scene::kBackgroundObjectId) beams[(std::uint64_t(f) << 32) | (std::uint64_t{ret.row} << 16) | ret.column].returns.push_back(ret);
    for (std::size_t f = 0; f < r.frames.size(); ++f)
        for (const Return& ret : r.frames[f].returns) {
            const auto it = beams.find((std::uint64_t(f) << 32) | (std::uint64_t{ret.row} << 16) | ret.column);
            if (it != beams.end()) it->second.all.push_back(ret);
        }
    return beams;
}

void print_returns(const char* label, const Beam& b) {
    std::printf("    %s:", label);
    for (const Return& r : b.all) std::printf("  [%.3f m %.1f pe obj %u]", r.range_m, r.intensity, r.object_id);
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 6) {
        std::fprintf(stderr, "usage: %s SCENARIO.json LINES_A SAMPLES_A LINES_B SAMPLES_B [FRAMES] [SHOWN]\n", argv[0]);
        return 2;
    }
    sensor_model::Scenario scenario = sensor_model::load_scenario(argv[1]);
    scenario.render.noise = false;
    const int frames = argc > 6 ? std::atoi(argv[6]) : 6;
    const int shown = argc > 7 ? std::atoi(argv[7]) : 40;
    std::vector<std::uint64_t> indices;
    if (frames < 0) indices.push_back(static_cast<std::uint64_t>(-frames));
    for (int k = 0; k < frames; ++k) indices.push_back(static_cast<std::uint64_t>(k) * static_cast<std::uint64_t>(scenario.render.frames) / frames);
    auto setting = [&](int lines, int samples) {
        if (lines > 0) return bench::with_map_reference(scenario, samples, lines);
        return bench::with_footprint(scenario, samples, samples > 0 ? 0.0 : sensor_model::RenderSettings{}.footprint_tolerance);
    };
    const bench::Rendering a = bench::render_frames(setting(std::atoi(argv[2]), std::atoi(argv[3])), indices);
    std::printf("A: %.2f s, %.0f beams/s\n", a.seconds, a.beams_per_second());
    const bench::Rendering b = bench::render_frames(setting(std::atoi(argv[4]), std::atoi(argv[5])), indices);
    std::printf("B: %.2f s, %.0f beams/s\n", b.seconds, b.beams_per_second());
    const auto beams_a = by_beam(a), beams_b = by_beam(b);
    struct Diff {
        std::uint64_t key;
        double error_m;
    };
    std::vector<Diff> diffs;
    double sum = 0.0;
    int off = 0, only_a = 0, only_b = 0;
    for (const auto& [key, beam] : beams_b) {
        const auto it = beams_a.find(key);
        if (it == beams_a.end()) {
            ++only_b;
            continue;
        }
        const double e = std::abs(it->second.returns.front().range_m - beam.returns.front().range_m);
        sum += e;
        off += e > 0.15;
        diffs.push_back({key, e});
    }
    for (const auto& [key, beam] : beams_a) only_a += !beams_b.contains(key);
    std::sort(diffs.begin(), diffs.end(), [](const Diff& x, const Diff& y) { return x.error_m > y.error_m; });
    std::printf("beams both %zu, only A %d, only B %d; mean first-return difference %.2f mm, median %.3f mm, off > 0.15 m %d (%.2f %%)\n",
                diffs.size(), only_a, only_b, diffs.empty() ? 0.0 : 1e3 * sum / double(diffs.size()),
                diffs.empty() ? 0.0 : 1e3 * diffs[diffs.size() / 2].error_m, off, diffs.empty() ? 0.0 : 100.0 * off / double(diffs.size()));
    // Beams where another object returned too (a target in front of the map, the terrain beyond):
    // their map is what the object leaves of the footprint.
    auto with_other = [&](const Beam& x) {
        return std::any_of(x.all.begin(), x.all.end(), [](const Return& r) { return r.object_id != scene::kBackgroundObjectId; });
    };
    double sum_other = 0.0;
    int off_other = 0, other = 0;
    for (const Diff& d : diffs) {
        if (!with_other(beams_a.at(d.key)) && !with_other(beams_b.at(d.key))) continue;
        ++other;
        sum_other += d.error_m;
        off_other += d.error_m > 0.15;
    }
    std::printf("of which beams with another object's return: %d, carrying %.2f mm of the mean, %d off\n", other,
                diffs.empty() ? 0.0 : 1e3 * sum_other / double(diffs.size()), off_other);
    double top = 0.0;
    for (std::size_t i = 0; i < diffs.size() && i < static_cast<std::size_t>(shown); ++i) top += diffs[i].error_m;
    std::printf("the %d largest carry %.1f %% of the summed difference\n", shown, sum > 0.0 ? 100.0 * top / sum : 0.0);
    for (std::size_t i = 0; i < diffs.size() && i < static_cast<std::size_t>(shown); ++i) {
        const std::uint64_t key = diffs[i].key;
        std::printf("frame %llu row %llu column %llu: %.3f m\n", static_cast<unsigned long long>(indices[key >> 32]),
                    static_cast<unsigned long long>((key >> 16) & 0xFFFF), static_cast<unsigned long long>(key & 0xFFFF), diffs[i].error_m);
        print_returns("A", beams_a.at(key));
        print_returns("B", beams_b.at(key));
    }
    return 0;
}
