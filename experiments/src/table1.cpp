#include "ladarsim/experiments/table1.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "ladarsim/sensor_model/signal/counter_random.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/core/units.h"

namespace ladarsim::experiments {

namespace {
}

AnalyticPointCount paper_point_count(double range_m, double fov_deg, double target_m, int beams_az, int beams_el,
                                     double divergence_mrad) {
    AnalyticPointCount p;
    p.fov_m = 2.0 * std::tan(0.5 * fov_deg * kDeg) * range_m;
    p.lines_az = static_cast<int>(std::ceil(target_m / (p.fov_m / beams_az)));
    p.lines_el = static_cast<int>(std::ceil(target_m / (p.fov_m / beams_el)));
    const double divergence_deg = divergence_mrad * kMrad / kDeg;
    auto intersection_m = [&](int beams) {
        return (divergence_deg * beams - fov_deg) / (beams - 1) * kDeg * range_m;
    };
    p.tbi_az_m = (0.5 * target_m + intersection_m(beams_az)) * 2.0;
    p.tbi_el_m = (0.5 * target_m + intersection_m(beams_el)) * 2.0;
    p.tp = std::ceil(p.tbi_az_m * beams_az / p.fov_m * p.tbi_el_m * beams_el / p.fov_m);
    return p;
}

const std::vector<PrintedTable1Row>& printed_table1() {
    static const std::vector<PrintedTable1Row> rows = {
        {200, 2.27, 20, 3, 0.519, 0.322, 105},  {500, 5.67, 8, 2, 0.848, 0.355, 46},
        {800, 9.08, 5, 1, 1.177, 0.389, 20},    {1100, 12.48, 4, 1, 1.506, 0.422, 19},
        {1400, 15.88, 3, 1, 1.834, 0.455, 18},  {1700, 19.29, 3, 1, 2.163, 0.489, 17},
        {2000, 22.69, 2, 1, 2.492, 0.522, 17},
    };
    return rows;
}

int rendered_point_count_at(const sensor_model::Sensor& sensor, int footprint_samples, std::shared_ptr<const scene::Model> target,
                            double range_m, double az_rad, double el_rad, bool noise, std::uint64_t seed,
                            std::uint64_t frame) {
    sensor_model::Scenario s;
    s.sensor = sensor;
    s.render.footprint_samples = footprint_samples;
    s.render.noise = noise;
    s.render.seed = seed;
    s.render.frames = 1;
    s.mount.gimbal_az_deg = 0.0;
    s.mount.gimbal_el_deg = 0.0;
    scene::SceneObject object;
    object.id = 1;
    object.model = std::move(target);
    // Facing the sensor: the model's +x (its nose, or the plate's normal) turned back towards it.
    const Eigen::Vector3d position =
        range_m * Eigen::Vector3d(std::cos(el_rad) * std::cos(az_rad), std::cos(el_rad) * std::sin(az_rad), std::sin(el_rad));
    object.trajectory = scene::Trajectory::fixed(
        scene::Pose{position, scene::orientation_from_ypr_deg(180.0 + az_rad / kDeg, -el_rad / kDeg, 0.0)});
    s.scene.objects.push_back(object);
    sensor_model::FrameRenderer renderer(s);
    const Frame f = renderer.render(frame);
    return static_cast<int>(
        std::count_if(f.returns.begin(), f.returns.end(), [](const Return& r) { return r.object_id == 1; }));
}

CountStatistics rendered_point_count(const sensor_model::Sensor& sensor, int footprint_samples, std::shared_ptr<const scene::Model> target,
                                     double range_m, int frames, bool noise, std::uint64_t seed,
                                     const std::function<void()>& frame_done) {
    const sensor_model::ScanPattern& scan = *sensor.scan;
    const double pitch_az = scan.field_az_deg() * kDeg / scan.columns();
    const double pitch_el = scan.field_el_deg() * kDeg / scan.rows();
    CountStatistics stats;
    for (int f = 0; f < frames; ++f) {
        // The sub-beam offset of this frame, from its own counter-based draw.
        const auto u = sensor_model::uniform4(seed, sensor_model::RandomStream::footprint_jitter, static_cast<std::uint64_t>(f), 0xFFFFFFFFu, 0);
        stats.per_frame.push_back(rendered_point_count_at(sensor, footprint_samples, target, range_m, (u[0] - 0.5) * pitch_az,
                                                          (u[1] - 0.5) * pitch_el, noise, seed, static_cast<std::uint64_t>(f)));
        if (frame_done) frame_done();
    }
    if (frames > 0) {
        double sum = 0.0, square = 0.0;
        for (int c : stats.per_frame) {
            sum += c;
            square += double(c) * c;
        }
        stats.mean = sum / frames;
        stats.stddev = std::sqrt(std::max(0.0, square / frames - stats.mean * stats.mean));
        stats.min = *std::min_element(stats.per_frame.begin(), stats.per_frame.end());
        stats.max = *std::max_element(stats.per_frame.begin(), stats.per_frame.end());
    }
    return stats;
}

nlohmann::json table1_comparison(const sensor_model::Sensor& sensor, int footprint_samples, std::shared_ptr<const scene::Model> plate,
                                 std::shared_ptr<const scene::Model> drone, int frames, std::uint64_t seed,
                                 const std::function<void(int, int)>& progress) {
    nlohmann::json rows = nlohmann::json::array();
    const auto& printed = printed_table1();
    const double target_m = 0.3;
    const sensor_model::ScanPattern& scan = *sensor.scan;
    constexpr int kRunsPerRange = 4;
    const int total_frames = static_cast<int>(printed.size()) * kRunsPerRange * frames;
    int done = 0;
    if (progress) progress(done, total_frames);
    const std::function<void()> frame_done = [&] {
        if (progress) progress(++done, total_frames);
    };
    for (const PrintedTable1Row& paper : printed) {
        const double r = paper.range_m;
        const AnalyticPointCount stated = paper_point_count(r, scan.field_az_deg(), target_m, scan.columns(), scan.rows(),
                                                            sensor.transmitter.divergence_mrad);
        const AnalyticPointCount wide =
            paper_point_count(r, 0.65, target_m, scan.columns(), scan.rows(), sensor.transmitter.divergence_mrad);
        nlohmann::json row = {
            {"range_m", r},
            {"paper_fov_m", paper.fov_m},
            {"paper_bl_az", paper.lines_az},
            {"paper_bl_el", paper.lines_el},
            {"paper_tbi_az_m", paper.tbi_az_m},
            {"paper_tbi_el_m", paper.tbi_el_m},
            {"paper_tp", paper.tp},
            {"analytic_fov_m_0p5deg", stated.fov_m},
            {"analytic_bl_az_0p5deg", stated.lines_az},
            {"analytic_bl_el_0p5deg", stated.lines_el},
            {"analytic_tp_0p5deg", stated.tp},
            {"analytic_fov_m_0p65deg", wide.fov_m},
            {"analytic_bl_az_0p65deg", wide.lines_az},
            {"analytic_bl_el_0p65deg", wide.lines_el},
            {"analytic_tbi_az_m_0p65deg", wide.tbi_az_m},
            {"analytic_tbi_el_m_0p65deg", wide.tbi_el_m},
            {"analytic_tp_0p65deg", wide.tp},
            {"lines_az_x_el_0p5deg", stated.lines_az * stated.lines_el},
        };
        const struct { const char* name; std::shared_ptr<const scene::Model> model; bool noise; } runs[kRunsPerRange] = {
            {"rendered_plate", plate, true}, {"rendered_plate_noiseless", plate, false},
            {"rendered_drone", drone, true}, {"rendered_drone_noiseless", drone, false}};
        for (const auto& run : runs) {
            const CountStatistics s = rendered_point_count(sensor, footprint_samples, run.model, r, frames, run.noise, seed, frame_done);
            const std::string n = run.name;
            row[n + "_mean"] = s.mean;
            row[n + "_stddev"] = s.stddev;
            row[n + "_min"] = s.min;
            row[n + "_max"] = s.max;
        }
        rows.push_back(row);
    }
    return rows;
}

std::string table1_markdown(const nlohmann::json& rows) {
    std::string md =
        "| range (m) | paper TP | Eq. 8, 0.5 deg | Eq. 8, 0.65 deg | BL_AZ x BL_EL, 0.5 deg | plate mean (sd) [min-max] | "
        "plate, no noise | drone mean (sd) [min-max] | drone, no noise |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
    char line[512];
    for (const auto& r : rows) {
        std::snprintf(line, sizeof line,
                      "| %.0f | %d | %.0f | %.0f | %d | %.1f (%.1f) [%d-%d] | %.1f | %.1f (%.1f) [%d-%d] | %.1f |\n",
                      r["range_m"].get<double>(), r["paper_tp"].get<int>(), r["analytic_tp_0p5deg"].get<double>(),
                      r["analytic_tp_0p65deg"].get<double>(), r["lines_az_x_el_0p5deg"].get<int>(),
                      r["rendered_plate_mean"].get<double>(), r["rendered_plate_stddev"].get<double>(),
                      r["rendered_plate_min"].get<int>(), r["rendered_plate_max"].get<int>(),
                      r["rendered_plate_noiseless_mean"].get<double>(), r["rendered_drone_mean"].get<double>(),
                      r["rendered_drone_stddev"].get<double>(), r["rendered_drone_min"].get<int>(),
                      r["rendered_drone_max"].get<int>(), r["rendered_drone_noiseless_mean"].get<double>());
        md += line;
    }
    return md;
}

}  // namespace ladarsim::experiments
