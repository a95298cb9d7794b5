#pragma once
// A real sensor's recorded frame as the scene it looked at, rendered again by the simulated unit
// at the recording's origin: which recorded returns come back, and at what range.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <numbers>
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/sensor_model/render/scenario.h"
#include "scratch_dir.h"

namespace ladarsim::test {

/// How a recorded return finds its rendered counterpart.
struct ReturnMatching {
    /// Same (row, column) cell: for a simulated unit that fires exactly the recorded beams (a
    /// channel table of the unit's own calibration).
    static ReturnMatching same_cell() { return {}; }
    /// The rendered return of the same row whose beam azimuth is nearest, if within
    /// `tolerance_rad`: for a unit whose recorded azimuths fall between the simulated beams.
    static ReturnMatching nearest_beam(double tolerance_rad) { return {true, tolerance_rad}; }
    bool by_azimuth = false;
    double tolerance_rad = 0.0;
};

/// What came back. Counted are the recorded returns within the simulated receiver's max_range_m;
/// those at reflectivity 0 (under 1 %: the map makes them black, though the unit saw them) apart.
struct RerenderFigures {
    std::size_t visible = 0, found = 0;    ///< recorded returns with reflectivity >= 1, and found again
    std::size_t dark = 0, dark_found = 0;  ///< recorded at reflectivity 0, and found again
    std::size_t rendered = 0;              ///< returns in the rendered frame
    double median_range_error_m = 0.0;     ///< |rendered - recorded| range, over those found
    double render_s = 0.0;                 ///< wall-clock time of rendering the frame (the scene already built)
    double found_share() const { return visible ? static_cast<double>(found) / static_cast<double>(visible) : 0.0; }
};

inline std::ostream& operator<<(std::ostream& out, const RerenderFigures& f) {
    return out << f.found << " of " << f.visible << " recorded returns found again (" << 100.0 * f.found_share()
               << " %), median range error " << f.median_range_error_m * 1e3 << " mm; " << f.dark_found << " of "
               << f.dark << " recorded at reflectivity 0; " << f.rendered << " rendered in " << f.render_s << " s";
}

/// Writes `recorded` into `dir` as recorded.pcd, makes it the background map of a scenario
/// (discs facing the recording's origin, reflectance = reflectivity / 100: the calibrated
/// reflectivity of Velodyne and Ouster, per cent for diffuse targets), puts the sensor `sensor`
/// (a scenario's "sensor" object: preset or file, plus overrides) at that origin and renders one
/// noise-free frame (render settings `render` added, e.g. footprint_samples); then finds each
/// recorded return's rendered one by `matching`.
inline RerenderFigures rerender_recorded(const ScratchDir& dir, const Frame& recorded, nlohmann::json sensor,
                                         ReturnMatching matching, const nlohmann::json& render = nlohmann::json::object()) {
    write_frame_pcd(dir / "recorded.pcd", recorded);
    sensor["position_m"] = {0, 0, 0};
    nlohmann::json scenario = {
        {"sensor", sensor},
        {"render", {{"frames", 1}, {"seed", 3}, {"noise", false}}},
        {"background", {{"file", "recorded.pcd"}, {"scanner_position_m", {0, 0, 0}}, {"reflectance_per_intensity", 0.01}}}};
    scenario["render"].update(render);
    std::ofstream(dir / "scene.json") << scenario.dump(2);
    const sensor_model::Scenario s = sensor_model::load_scenario(dir / "scene.json");
    sensor_model::FrameRenderer renderer(s);
    const auto start = std::chrono::steady_clock::now();
    const Frame rendered = renderer.render(0);
    RerenderFigures figures;
    figures.render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    figures.rendered = rendered.returns.size();

    // Rendered returns by row; the first of each cell (noise off, strongest return: one a cell).
    std::vector<std::vector<const Return*>> by_row(static_cast<std::size_t>(rendered.rows));
    for (const Return& r : rendered.returns) by_row[r.row].push_back(&r);
    auto counterpart = [&](const Return& r) -> const Return* {
        if (r.row >= by_row.size()) return nullptr;
        const auto& row = by_row[r.row];
        if (!matching.by_azimuth) {
            const auto it = std::lower_bound(row.begin(), row.end(), r.column, [](const Return* q, int c) { return q->column < c; });
            return it != row.end() && (*it)->column == r.column ? *it : nullptr;
        }
        const Return* nearest = nullptr;
        double best = matching.tolerance_rad;
        for (const Return* q : row) {
            const double d = std::abs(std::remainder(q->beam_az_rad - r.beam_az_rad, 2.0 * std::numbers::pi));
            if (d < best) best = d, nearest = q;
        }
        return nearest;
    };
    std::vector<double> range_errors;
    for (const Return& r : recorded.returns) {
        if (r.range_m >= s.sensor.receiver.max_range_m) continue;
        const Return* back = counterpart(r);
        if (r.intensity < 1) {
            ++figures.dark;
            figures.dark_found += back != nullptr;
            continue;
        }
        ++figures.visible;
        if (!back) continue;
        ++figures.found;
        range_errors.push_back(std::abs(back->range_m - r.range_m));
    }
    if (!range_errors.empty()) {
        const auto middle = range_errors.begin() + static_cast<std::ptrdiff_t>(range_errors.size() / 2);
        std::nth_element(range_errors.begin(), middle, range_errors.end());
        figures.median_range_error_m = *middle;
    }
    return figures;
}

}  // namespace ladarsim::test
