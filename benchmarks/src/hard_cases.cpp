#include "hard_cases.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <vector>

#include "bench_frames.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/signal/beam_receiver.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/sensor_model/signal/range_equation.h"
#include "ladarsim/core/units.h"

namespace ladarsim::bench {

namespace {

using nlohmann::json;
using sensor_model::Scenario;

constexpr int kReferenceSamples = 4096;
/// Every object's returns count (no one object in focus).
constexpr std::uint32_t kAllObjects = 0xFFFFFFFEu;

/// One hard case: a scenario (noise off), the frames rendered, the object whose returns are judged,
/// and for extended targets the echo of a footprint filled by the target, per beam.
struct HardCase {
    std::string name;
    Scenario scenario;
    std::vector<std::uint64_t> frames;
    std::uint32_t object_id = kAllObjects;
    std::function<double(const Return&)> full_echo_pe;  ///< empty when not an extended target
    std::function<bool(const Return&)> judged;          ///< empty: every beam is judged
    /// The same scene at an easier pointing, timed for comparison (the horizon against -2 deg).
    std::optional<Scenario> easier;
    /// Over a recorded map: the reference's scanline lines (its convergence shown against twice
    /// as many); 0: kReferenceSamples sub-rays.
    int reference_lines = 0;
};

/// A first return this far from the reference's is another surface's, not the same one's.
constexpr double kOffRange_m = 0.15;

/// Detection threshold of a beam's unstretched pulse, in primary photo-electrons.
double threshold_pe(const Scenario& s) {
    const sensor_model::BeamReceiver receiver(s.sensor, s.atmosphere, false);
    const auto& apd = receiver.apd();
    return apd.threshold_a() / (apd.amps_per_watt() * receiver.waveform().pulse().peak_per_joule()) *
           s.sensor.receiver.responsivity_a_per_w / sensor_model::kElementaryCharge_c;
}

/// What one rendering reports against the reference, beam by beam (object `id`'s returns, or all).
struct BeamErrors {
    std::uint64_t returns = 0, reference_returns = 0;
    int missing_beams = 0;          ///< reference echo over 5x the threshold, nothing reported
    int extra_beams = 0;            ///< reported where the reference reports nothing
    double energy_error_pct = 0.0;  ///< sum over beams of |energy - reference| over the reference's sum
    double max_fraction_error = 0.0;///< largest |energy - reference| / full echo (extended targets)
    double range_error_mm = 0.0;    ///< mean |first range - reference| over beams both report
    double beams_off_pct = 0.0;     ///< of beams both report, those whose first ranges differ by > kOffRange_m
    /// The part of beams_off_pct whose beam the reference also sees a drone, bird or aircraft in
    /// (in front of the map): where the judged object's error comes from.
    double beams_off_with_targets_pct = 0.0;
    double total_energy_error_pct = 0.0;  ///< summed energy against the reference's
    /// Their median: a few beams whose first return is another surface's (one reports a weak near
    /// return the other does not) dominate the mean at grazing incidence.
    double median_range_error_mm = 0.0;
};

BeamErrors compare_beams(const HardCase& c, const Rendering& r, const Rendering& reference) {
    struct Beam {
        int returns = 0;
        double energy_pe = 0.0;
        double first_range_m = 0.0;
        double full_echo_pe = 0.0;
    };
    auto tally = [&](const Rendering& x) {
        std::map<std::uint64_t, Beam> beams;
        for (std::size_t f = 0; f < x.frames.size(); ++f) {
            for (const Return& ret : x.frames[f].returns) {
                if (c.object_id != kAllObjects && ret.object_id != c.object_id) continue;
                if (c.judged && !c.judged(ret)) continue;
                Beam& b = beams[(std::uint64_t(f) << 32) | (std::uint64_t{ret.row} << 16) | ret.column];
                if (b.returns++ == 0) {
                    b.first_range_m = ret.range_m;
                    if (c.full_echo_pe) b.full_echo_pe = c.full_echo_pe(ret);
                }
                b.energy_pe += ret.intensity;
            }
        }
        return beams;
    };
    const auto got = tally(r), want = tally(reference);
    std::set<std::uint32_t> targets;
    for (const scene::SceneObject& o : c.scenario.scene.objects)
        if (o.id != c.object_id && (o.object_class == scene::ObjectClass::drone || o.object_class == scene::ObjectClass::bird ||
                                    o.object_class == scene::ObjectClass::plane))
            targets.insert(o.id);
    std::set<std::uint64_t> with_targets;
    for (std::size_t f = 0; f < reference.frames.size(); ++f)
        for (const Return& ret : reference.frames[f].returns)
            if (targets.contains(ret.object_id)) with_targets.insert((std::uint64_t(f) << 32) | (std::uint64_t{ret.row} << 16) | ret.column);
    const double threshold = threshold_pe(c.scenario);
    BeamErrors e;
    double abs_sum = 0.0, ref_sum = 0.0, range_sum = 0.0, got_sum = 0.0;
    int off = 0, off_with_targets = 0;
    std::vector<double> range_errors;
    int both = 0;
    for (const auto& [key, b] : got) {
        e.returns += static_cast<std::uint64_t>(b.returns);
        got_sum += b.energy_pe;
    }
    for (const auto& [key, w] : want) {
        e.reference_returns += static_cast<std::uint64_t>(w.returns);
        ref_sum += w.energy_pe;
        const auto it = got.find(key);
        const double energy = it == got.end() ? 0.0 : it->second.energy_pe;
        abs_sum += std::abs(energy - w.energy_pe);
        if (w.full_echo_pe > 0.0) e.max_fraction_error = std::max(e.max_fraction_error, std::abs(energy - w.energy_pe) / w.full_echo_pe);
        if (it == got.end()) {
            e.missing_beams += w.energy_pe > 5.0 * threshold;
            continue;
        }
        range_sum += std::abs(it->second.first_range_m - w.first_range_m);
        range_errors.push_back(std::abs(it->second.first_range_m - w.first_range_m));
        off += range_errors.back() > kOffRange_m;
        off_with_targets += range_errors.back() > kOffRange_m && with_targets.contains(key);
        ++both;
    }
    for (const auto& [key, b] : got) {
        if (want.contains(key)) continue;
        ++e.extra_beams;
        abs_sum += b.energy_pe;
        if (b.full_echo_pe > 0.0) e.max_fraction_error = std::max(e.max_fraction_error, b.energy_pe / b.full_echo_pe);
    }
    e.energy_error_pct = ref_sum > 0.0 ? 100.0 * abs_sum / ref_sum : 0.0;
    e.range_error_mm = both ? 1e3 * range_sum / both : 0.0;
    e.beams_off_pct = both ? 100.0 * off / both : 0.0;
    e.beams_off_with_targets_pct = both ? 100.0 * off_with_targets / both : 0.0;
    e.total_energy_error_pct = ref_sum > 0.0 ? 100.0 * (got_sum - ref_sum) / ref_sum : 0.0;
    if (!range_errors.empty()) {
        const auto middle = range_errors.begin() + static_cast<std::ptrdiff_t>(range_errors.size() / 2);
        std::nth_element(range_errors.begin(), middle, range_errors.end());
        e.median_range_error_mm = 1e3 * *middle;
    }
    return e;
}

/// The paper's sensor on a strip of its raster (same beam pitch, `columns` wide), at the origin,
/// looking along +x; noise, extinction, folding and saturation off.
Scenario plain_scenario(int columns) {
    Scenario s;
    s.sensor = sensor_model::sensor_preset("paper_ladar");
    auto p = dynamic_cast<const sensor_model::GalvoRaster&>(*s.sensor.scan).parameters();
    p.field_az_deg *= double(columns) / p.beams_az;
    p.beams_az = columns;
    s.sensor.scan = std::make_shared<sensor_model::GalvoRaster>(p);
    s.sensor.receiver.range_folding = false;
    s.sensor.receiver.saturation_current_a = 1e6;
    s.atmosphere.visibility_m = std::numeric_limits<double>::infinity();
    s.mount.gimbal_az_deg = 0.0;
    s.mount.gimbal_el_deg = 0.0;
    s.render.frames = 1;
    s.render.noise = false;
    return s;
}

/// A 40 m plate (reflectance 0.5) at `distance_m` facing the sensor, one straight edge through the
/// boresight: vertical (the plate to the left), horizontal (below) or diagonal (45 deg, below left).
HardCase straight_edge(const std::string& orientation, double distance_m) {
    constexpr double kSide = 40.0, kReflectance = 0.5;
    HardCase c;
    c.name = "straight edge, " + orientation + ", " + std::to_string(int(distance_m)) + " m";
    c.scenario = plain_scenario(32);
    c.frames = {0};
    c.object_id = 1;
    double roll = 0.0;
    Eigen::Vector3d centre(distance_m, 0.0, 0.0);
    const double h = 0.5 * kSide;
    if (orientation == "vertical") centre.y() = h;
    else if (orientation == "horizontal") centre.z() = -h;
    else {
        roll = 45.0;
        centre.y() = h * std::numbers::sqrt2 / 2.0;
        centre.z() = -h * std::numbers::sqrt2 / 2.0;
    }
    scene::SceneObject plate;
    plate.id = 1;
    plate.object_class = scene::ObjectClass::building;
    plate.model = std::make_shared<scene::Model>(scene::make_plate(kSide, kReflectance));
    plate.trajectory = scene::Trajectory::fixed(scene::Pose{centre, scene::orientation_from_ypr_deg(0, 0, roll)});
    c.scenario.scene.objects.push_back(plate);
    const sensor_model::Sensor sensor = c.scenario.sensor;
    // The plate filling the footprint at the beam's range: the extended-target closed form.
    c.full_echo_pe = [sensor, distance_m](const Return& r) {
        const double cos_axis = std::cos(r.beam_az_rad) * std::cos(r.beam_el_rad);
        const double range = distance_m / cos_axis;
        const double energy = sensor_model::lambertian_echo_energy_j(
            sensor.transmitter.pulse_energy_j(), 1.0, sensor.optics.optics_efficiency, 1.0, kReflectance, cos_axis,
            sensor.optics.aperture_area_m2(), range);
        return energy * sensor.receiver.responsivity_a_per_w / sensor_model::kElementaryCharge_c;
    };
    return c;
}

/// The default scenario without its drone, the gimbal held level (0 deg) over the modelled
/// terrain: footprints graze the ground and reach to the ridge 2 km out; timed against the same
/// scene 2 deg down.
HardCase horizon(const Scenario& base) {
    HardCase c;
    c.name = "horizon, 0 deg over the terrain";
    c.scenario = base;
    std::erase_if(c.scenario.scene.objects, [&](const scene::SceneObject& o) { return o.id == base.mount.cue_object_id; });
    c.scenario.mount.cue_object_id = 0;
    c.scenario.mount.gimbal_az_deg = 0.0;
    c.scenario.mount.gimbal_el_deg = 0.0;
    c.scenario.render.noise = false;
    c.frames = {0, 1, 2, 3, 4};  // frames of a few milliseconds: several, for a steadier speed
    c.easier = c.scenario;
    c.easier->mount.gimbal_el_deg = -2.0;
    return c;
}

constexpr const char* kRecordedMapCase = "recorded map, dataset 2 over Autzen";

/// Dataset 2 over the recorded Autzen map: sight lines graze the survey's ground 600-960 m out.
std::optional<HardCase> recorded_map(const BenchOptions& options) {
    HardCase c;
    c.name = kRecordedMapCase;
    try {
        c.scenario = sensor_model::load_scenario(options.map_scenario);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    c.scenario.render.noise = false;
    const auto frames = static_cast<std::uint64_t>(c.scenario.render.frames);
    const std::uint64_t count = options.quick ? 2 : 6;
    for (std::uint64_t k = 0; k < count; ++k) c.frames.push_back(k * frames / count);
    c.object_id = scene::kBackgroundObjectId;
    c.reference_lines = kMapReferenceLines;
    return c;
}

/// A 60 m cloud (30 /km) at 640 m whose outline crosses the boresight, nothing behind it.
HardCase cloud_edge() {
    HardCase c;
    c.name = "cloud edge, 640 m";
    c.scenario = plain_scenario(32);
    c.frames = {0};
    scene::SceneObject cloud;
    cloud.id = 40;
    cloud.object_class = scene::ObjectClass::cloud;
    cloud.model = std::make_shared<scene::Model>(scene::make_cloud(60.0, 0.03));
    cloud.trajectory = scene::Trajectory::fixed(scene::Pose{{640.0, 30.0, 0.0}, Eigen::Quaterniond::Identity()});
    c.scenario.scene.objects.push_back(cloud);
    c.object_id = cloud.id;
    return c;
}

/// The quadcopter at 1000 m before the terrain (seen from 40 m up, 2 deg down), judged on the beams that hold it beyond half the
/// footprint's radius from their axis.
HardCase drone_at_footprint_edge(const Scenario& base) {
    HardCase c;
    c.name = "drone at the footprint's edge, 1000 m";
    c.scenario = plain_scenario(32);
    c.frames = {0, 1, 2};
    c.scenario.render.frames = 3;
    c.scenario.mount.position_world = {0.0, 0.0, 40.0};
    c.scenario.mount.gimbal_el_deg = -2.0;
    const Eigen::Vector3d boresight(std::cos(2.0 * kDeg), 0.0, -std::sin(2.0 * kDeg));
    for (const scene::SceneObject& o : base.scene.objects) {
        if (o.id == base.mount.cue_object_id) {
            scene::SceneObject drone = o;
            drone.trajectory = scene::Trajectory::fixed(scene::Pose{c.scenario.mount.position_world + 1000.0 * boresight, Eigen::Quaterniond::Identity()});
            c.scenario.scene.objects.push_back(drone);
            c.object_id = o.id;
        } else if (o.object_class == scene::ObjectClass::terrain) {
            c.scenario.scene.objects.push_back(o);
        }
    }
    const double r_max = c.scenario.render.footprint_truncation * 0.5 * c.scenario.sensor.transmitter.divergence_mrad * kMrad;
    c.judged = [r_max, boresight](const Return& r) {
        const Eigen::Vector3d axis(std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad), std::cos(r.beam_el_rad) * std::sin(r.beam_az_rad),
                                   std::sin(r.beam_el_rad));
        return std::acos(std::min(1.0, axis.dot(boresight))) > 0.5 * r_max;
    };
    return c;
}

/// A quadcopter 450 m out with three birds 17 m in front of it and a fourth beside it, all flying,
/// seen 3.4 deg up (dataset 2's flock): sparse targets sharing footprints; the drone's returns judged.
HardCase drone_behind_birds() {
    HardCase c;
    c.name = "drone behind birds, 450 m";
    c.scenario = plain_scenario(32);
    c.frames = {0, 1, 2};
    c.scenario.render.frames = 3;
    c.scenario.mount.gimbal_el_deg = std::atan2(27.0, 450.0) / kDeg;
    auto flying = [](std::uint32_t id, scene::ObjectClass object_class, scene::Model model, const Eigen::Vector3d& at,
                     const Eigen::Vector3d& velocity_mps) {
        scene::SceneObject o;
        o.id = id;
        o.object_class = object_class;
        o.model = std::make_shared<const scene::Model>(std::move(model));
        o.trajectory = scene::Trajectory::keyframes({{0.0, {at, Eigen::Quaterniond::Identity()}},
                                                     {10.0, {at + 10.0 * velocity_mps, Eigen::Quaterniond::Identity()}}},
                                                    scene::Interpolation::linear);
        return o;
    };
    c.scenario.scene.objects.push_back(flying(1, scene::ObjectClass::drone, scene::make_quadcopter(), {450.0, 0.0, 27.0}, {0.0, 0.5, 0.0}));
    const Eigen::Vector3d birds[] = {{433.0, 0.25, 26.1}, {433.0, -0.2, 25.85}, {433.0, 0.1, 25.65}, {450.0, 0.0, 28.2}};
    std::uint32_t id = 20;
    for (const Eigen::Vector3d& at : birds)
        c.scenario.scene.objects.push_back(flying(id++, scene::ObjectClass::bird, scene::make_bird(0.45), at, {-5.0, 0.0, 0.2}));
    c.object_id = 1;
    return c;
}

/// The same flock with every return judged: the birds' energy, which the drone's alone does not show
/// (the outline's refinement once weighed the birds' sparse wings 8 % low in dataset 2).
HardCase flock_every_return() {
    HardCase c = drone_behind_birds();
    c.name = "drone and birds, every return, 450 m";
    c.object_id = kAllObjects;
    return c;
}

struct Setting {
    int samples;
    double tolerance;
    /// The reference again with another seed (other jitter and volume draws): how far the
    /// reference itself is from converged, the floor under every other setting's error.
    bool another_seed = false;
};

json run_case(const HardCase& c, const BenchOptions& options, const std::vector<Setting>& settings, double default_tolerance) {
    options.progress("hard case: " + c.name + ", reference");
    auto reference_of = [&](int lines) {
        return lines ? with_map_reference(c.scenario, kReferenceSamples, lines) : with_footprint(c.scenario, kReferenceSamples, 0.0);
    };
    const Rendering reference = render_frames(reference_of(c.reference_lines), c.frames);
    json about_reference = {{"method", std::to_string(kReferenceSamples) + " fixed sub-rays a beam"}};
    if (c.reference_lines) {
        options.progress("hard case: " + c.name + ", reference at twice its lines");
        const BeamErrors self = compare_beams(c, render_frames(reference_of(2 * c.reference_lines), c.frames), reference);
        about_reference = {{"method", "scanline over the map's discs, " + std::to_string(c.reference_lines) + " lines a beam, " +
                                          std::to_string(kReferenceSamples / c.reference_lines) +
                                          " rays a line for other objects, split over a target's outline into cells as fine "
                                          "across the line as the lines are apart"},
                           {"against", std::to_string(2 * c.reference_lines) + " lines"},
                           {"self_difference_mean_mm", self.range_error_mm},
                           {"self_difference_median_mm", self.median_range_error_mm},
                           {"self_difference_beams_off_pct", self.beams_off_pct},
                           {"self_difference_count_pct", self.reference_returns ? 100.0 * (double(self.returns) - double(self.reference_returns)) /
                                                                                      double(self.reference_returns)
                                                                                : 0.0},
                           {"self_difference_energy_pct", self.total_energy_error_pct}};
    }
    json rows = json::array();
    for (const Setting& s : settings) {
        Scenario scenario = with_footprint(c.scenario, s.samples, s.tolerance);
        if (s.another_seed) ++scenario.render.seed;
        const Rendering r = render_frames(scenario, c.frames);
        const BeamErrors e = compare_beams(c, r, reference);
        json row = {{"footprint_samples", s.samples},
                    {"footprint_tolerance", s.tolerance},
                    {"beams_per_s", r.beams_per_second()},
                    {"rays_per_beam", r.rays_per_beam()},
                    {"returns", e.returns},
                    {"reference_returns", e.reference_returns},
                    {"count_error_pct", e.reference_returns ? 100.0 * (double(e.returns) - double(e.reference_returns)) /
                                                                  double(e.reference_returns)
                                                            : 0.0},
                    {"missing_beams", e.missing_beams},
                    {"extra_beams", e.extra_beams},
                    {"energy_error_pct", e.total_energy_error_pct},
                    {"beam_energy_error_pct", e.energy_error_pct},
                    {"mean_first_return_error_mm", e.range_error_mm},
                    {"median_first_return_error_mm", e.median_range_error_mm},
                    {"beams_off_pct", e.beams_off_pct}};
        if (c.object_id == scene::kBackgroundObjectId) row["beams_off_with_targets_pct"] = e.beams_off_with_targets_pct;
        if (c.full_echo_pe) row["max_energy_fraction_error"] = e.max_fraction_error;
        if (s.samples == 0 && s.tolerance == default_tolerance) row["default"] = true;
        if (s.another_seed) row["reference_with_another_seed"] = true;
        if (c.easier) {
            const Rendering easier = render_frames(with_footprint(*c.easier, s.samples, s.tolerance), c.frames);
            row["easier_beams_per_s"] = easier.beams_per_second();
            row["speed_vs_easier"] = r.beams_per_second() / easier.beams_per_second();
        }
        rows.push_back(row);
    }
    return {{"case", c.name}, {"frames", c.frames.size()}, {"reference", about_reference}, {"settings", rows}};
}

}  // namespace

json hard_cases(const Scenario& scenario, const BenchOptions& options, const std::string& only) {
    const double default_tolerance = sensor_model::RenderSettings{}.footprint_tolerance;
    std::vector<Setting> settings = {{0, 0.2}, {0, default_tolerance}, {0, 0.01}, {64, 0.0}, {kReferenceSamples, 0.0, true}};
    if (options.quick) settings = {{0, default_tolerance}, {64, 0.0}, {kReferenceSamples, 0.0, true}};
    const auto wanted = [&](const std::string& name) { return only.empty() || name.find(only) != std::string::npos; };
    std::vector<HardCase> cases;
    for (const char* orientation : {"vertical", "horizontal", "diagonal"})
        for (const double distance : {200.0, 1000.0, 2000.0}) cases.push_back(straight_edge(orientation, distance));
    cases.push_back(horizon(scenario));
    // Loading the survey takes longer than most cases run: only when the map's case is asked for.
    if (wanted(kRecordedMapCase))
        if (auto map = recorded_map(options)) cases.push_back(std::move(*map));
    cases.push_back(cloud_edge());
    cases.push_back(drone_at_footprint_edge(scenario));
    cases.push_back(drone_behind_birds());
    cases.push_back(flock_every_return());
    json result = json::array();
    for (const HardCase& c : cases) {
        if (!wanted(c.name)) continue;
        result.push_back(run_case(c, options, settings, default_tolerance));
    }
    return result;
}

}  // namespace ladarsim::bench
