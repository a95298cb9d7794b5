// Adaptive footprints against closed forms and against brute force: each shortcut gives the answer
// of the full path within its tolerance, small targets are found, and the error falls as the
// tolerance tightens.
#include <catch2/catch.hpp>

#include <string>
#include <cmath>
#include <filesystem>
#include <array>
#include <map>
#include <set>
#include <random>
#include <vector>
#include <algorithm>

#include "ladarsim/sensor_model/signal/apd_receiver.h"
#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "../support/closed_form_scenario.h"
#include "../support/footprint_grid.h"
#include "../support/sensors.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

/// Share of a beam's energy on a square of half-side `half_m` facing it at `distance_m` on the
/// sensor's x axis, turned by `roll` about that axis, for a beam pointing (az, el): the Gaussian
/// (sigma = divergence / 4 per axis) is round and separable, so in axes turned with the square the
/// share is a product of two normal-CDF differences, over F = 1 - exp(-4.5) for the truncated
/// footprint's renormalisation. Valid while the square lies well inside the truncation radius.
double plate_share(const Sensor& c, double half_m, double distance_m, double roll, double az, double el) {
    const double sigma = 0.25 * c.transmitter.divergence_mrad * 1e-3;
    const double half = std::atan(half_m / distance_m);
    auto axis = [&](double centre) { return normal_cdf((centre + half) / sigma) - normal_cdf((centre - half) / sigma); };
    const double captured = -std::expm1(-2.0 * kTruncation * kTruncation);
    const double u = -az * std::cos(roll) - el * std::sin(roll), v = az * std::sin(roll) - el * std::cos(roll);
    return axis(u) * axis(v) / captured;
}

/// Detection threshold of a beam's unstretched pulse, in primary photo-electrons.
double threshold_photoelectrons(const Scenario& s) {
    const BeamReceiver receiver(s.sensor, s.atmosphere, false);
    const auto& apd = receiver.apd();
    return apd.threshold_a() / (apd.amps_per_watt() * receiver.waveform().pulse().peak_per_joule()) *
           s.sensor.receiver.responsivity_a_per_w / kElementaryCharge_c;
}

struct PlateRun {
    int returns = 0;
    int expected_detectable = 0;  ///< beams whose closed-form energy is twice the threshold's
    int found_detectable = 0;
    double abs_error = 0.0, expected = 0.0, rendered = 0.0;  ///< summed |intensity - closed form|, closed form, intensity
    double rays_per_beam = 0.0;
};

/// A 0.1 m plate (reflectance 1) at `distance_m` on the axis, nothing behind it; turned 45 deg
/// about the axis, a diamond filling half its outline, whose edges cut the sampled cells.
PlateRun plate_run(int samples, double tolerance, double distance_m, double roll_deg = 45.0) {
    Scenario s = closed_form_scenario();
    s.render.footprint_samples = samples;
    s.render.footprint_tolerance = tolerance;
    const double half = 0.05;
    s.scene.objects.push_back(object_at(1, plate(2 * half, 1.0),
                                        scene::Trajectory::fixed(scene::Pose{{distance_m, 0.0, 0.0},
                                                                             scene::orientation_from_ypr_deg(0, 0, roll_deg)})));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);
    const double threshold_pe = threshold_photoelectrons(s);
    const double full = extended_target_photoelectrons(s.sensor, 1.0, 1.0, distance_m);
    const double r_max = s.render.footprint_truncation * 0.5 * s.sensor.transmitter.divergence_mrad * 1e-3;

    std::map<int, const Return*> seen;
    for (const Return& r : f.returns) seen[r.row * 1000 + r.column] = &r;
    PlateRun run;
    run.rays_per_beam = double(renderer.rays_last_frame()) / renderer.raster().beam_count();
    const ScanPattern& raster = renderer.raster();
    for (int row = 0; row < raster.rows(); ++row) {
        for (int step = 0; step < raster.columns(); ++step) {
            const RasterBeam b = raster.beam(row, step);
            // Only where the plate is well inside the truncated footprint (the closed form ignores truncation).
            if (std::hypot(b.az_offset_rad, b.el_offset_rad) + 1.5 * half / distance_m > r_max) continue;
            const double expected =
                full * plate_share(s.sensor, half, distance_m, roll_deg * M_PI / 180.0, b.az_offset_rad, b.el_offset_rad);
            const auto it = seen.find(b.row * 1000 + b.column);
            const double got = it == seen.end() ? 0.0 : it->second->intensity;
            if (expected > 2.0 * threshold_pe) {
                ++run.expected_detectable;
                run.found_detectable += it != seen.end();
                run.abs_error += std::abs(got - expected);
                run.rendered += got;
                run.expected += expected;
            }
        }
    }
    return run;
}

}  // namespace

TEST_CASE("a plane patch integrated without rays equals brute force on a tilted wall", "[footprint]") {
    // A wall at 100 m turned 60 or 85 deg (grazing), or turned its back to the sensor: every
    // footprint lies on one plane, across which the range changes by up to 20 cm and cos(theta)
    // by up to 15 %.
    const double yaw_deg = GENERATE(60.0, 85.0, 180.0);
    INFO("wall turned " << yaw_deg << " deg");
    auto render = [yaw_deg](int samples) {
        Scenario s = closed_form_scenario();
        s.render.jitter = false;
        s.render.footprint_samples = samples;
        s.scene.objects.push_back(object_at(1, plate(800.0, 0.4),
                                            scene::Trajectory::fixed(scene::Pose{
                                                {100.0, 0.0, 0.0}, scene::orientation_from_ypr_deg(yaw_deg, 0, 0)})));
        FrameRenderer renderer(s);
        Frame f = renderer.render(0);
        return std::make_pair(std::move(f), renderer.rays_last_frame());
    };
    const auto [adaptive, adaptive_rays] = render(0);
    const auto [brute, brute_rays] = render(4096);
    REQUIRE(adaptive.returns.size() == brute.returns.size());
    for (std::size_t i = 0; i < adaptive.returns.size(); ++i) {
        const Return& a = adaptive.returns[i];
        const Return& b = brute.returns[i];
        REQUIRE(a.column == b.column);
        REQUIRE(a.row == b.row);
        // 16 quadrature nodes against 4096 sub-rays: the range to a millimetre and the intensity
        // to 0.5 %, both read from the stretched pulse, so both depend on the range spread (the
        // nodes' spread scaled by Footprint::variance_over_fixed: unscaled, 6 mm and 2.8 % at 85 deg).
        CHECK(a.range_m == Approx(b.range_m).margin(1e-3));
        CHECK(a.intensity == Approx(b.intensity).epsilon(5e-3));
    }
    // One probe ray per beam (plus a few at the raster's border) against 4096.
    CHECK(adaptive_rays < 1.2 * 3000);
}

TEST_CASE("a target smaller than the sub-ray spacing is found and weighed by its footprint share", "[footprint]") {
    // At 1 km the 0.1 m plate subtends 0.1 mrad: less than the 0.2 mrad between 16 fixed sub-rays.
    const PlateRun adaptive = plate_run(0, 0.02, 1000.0);
    REQUIRE(adaptive.expected_detectable > 3);
    CHECK(adaptive.found_detectable == adaptive.expected_detectable);
    CHECK(adaptive.abs_error / adaptive.expected < 0.03);
    const PlateRun fixed = plate_run(16, 0.0, 1000.0);
    INFO("16 fixed sub-rays find " << fixed.found_detectable << " of " << fixed.expected_detectable);
    CHECK(fixed.abs_error / fixed.expected > 3.0 * adaptive.abs_error / adaptive.expected);
}

TEST_CASE("the error on a small target falls as the tolerance tightens, and costs rays", "[footprint]") {
    // A 0.1 m plate at 2 km: 0.05 mrad across, 2.5 % of the footprint's area.
    double last_error = 1e9, last_rays = 0.0;
    for (const double tolerance : {0.3, 0.1, 0.03, 0.01}) {
        const PlateRun run = plate_run(0, tolerance, 2000.0);
        REQUIRE(run.expected_detectable > 0);
        const double error = run.abs_error / run.expected;
        INFO("tolerance " << tolerance << ": error " << error << ", " << run.rays_per_beam << " rays per beam");
        CHECK(error <= last_error * 1.05);
        CHECK(error < tolerance);
        CHECK(run.rays_per_beam >= last_rays);
        last_error = error;
        last_rays = run.rays_per_beam;
    }
}

TEST_CASE("from a 10 m wall to a small plate at 2 km, each energy matches its closed form", "[footprint]") {
    // Extended targets (R^-2) from 10 m to 2 km, and a small plate at 2 km (R^-4): more than six
    // decades of received energy, each against its closed form.
    double near_rendered = 0.0;
    for (const double distance : {10.0, 2000.0}) {
        Scenario s = closed_form_scenario();
        s.scene.objects.push_back(object_at(1, plate(100.0, 0.5), fixed_at(distance, 0, 0)));
        FrameRenderer renderer(s);
        const Frame f = renderer.render(0);
        REQUIRE(f.returns.size() == 3000u);
        for (const Return& r : f.returns) {
            const double cos_axis = std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad);
            const double range = distance / cos_axis;
            CHECK(r.range_m == Approx(range).margin(1e-4));
            // The intensity is read from the pulse's peak: a beam 4 mrad off the wall's normal at
            // 2 km spans 1.4 mm of range, and its peak is 2e-4 lower for it.
            const double peak_share = test::discriminated_echo(s.sensor, s.render.footprint_truncation, [&](double x, double y) {
                const double c = std::cos(r.beam_el_rad + y) * std::cos(r.beam_az_rad + x);
                return std::pair{distance / c, c * c * c};
            }, 100).peak_share;
            CHECK(r.intensity == Approx(peak_share * extended_target_photoelectrons(s.sensor, 0.5, cos_axis, range)).epsilon(1e-4));
            if (distance == 10.0) near_rendered = std::max(near_rendered, double(r.intensity));
        }
    }
    const PlateRun far = plate_run(0, 0.01, 2000.0);
    CHECK(far.abs_error / far.expected < 0.01);
    // What was rendered spans more than six decades, each end matching its closed form.
    CHECK(near_rendered / (far.rendered / far.expected_detectable) > 1e6);
}

TEST_CASE("a black surface (reflectance 0) is a plane patch that returns nothing, not NaN", "[footprint]") {
    // Recorded maps hold points of intensity 0: the plane's model energy is then 0 as well, and
    // the patch must not divide one by the other. A bright plate in front of the black wall puts
    // two surfaces 0.2 m apart in the beams around it, whose pulses overlap in one waveform.
    Scenario s = closed_form_scenario();
    s.render.noise = true;
    s.scene.objects.push_back(object_at(1, plate(800.0, 0.0), fixed_at(100.0, 0.0, 0.0)));
    s.scene.objects.push_back(object_at(2, plate(0.3, 0.5), fixed_at(99.8, 0.0, 0.0)));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);
    int plate_returns = 0;
    for (const Return& r : f.returns) {
        REQUIRE(std::isfinite(r.range_m));
        CHECK(r.object_id != 1);
        plate_returns += r.object_id == 2;
    }
    CHECK(plate_returns > 0);
}

TEST_CASE("straight edges of an extended object: no beam missing, every energy within 2 % of the footprint's", "[footprint][edges]") {
    // A 40 m plate (reflectance 0.5) facing the sensor with one straight edge through the boresight,
    // at 200 and 1000 m, against 4096 fixed sub-rays per beam rendered here (noise off): on a strip
    // of the paper's raster (its pitch, 24 columns), every beam the reference sees at more than 5x
    // the threshold is reported, and each beam's energy, as a fraction of the plate filling its
    // footprint (the extended-target closed form), is within 0.02 of the reference's.
    const std::string orientation = GENERATE(as<std::string>{}, "vertical", "horizontal", "diagonal");
    const double distance_m = GENERATE(200.0, 1000.0);
    INFO(orientation << " edge at " << distance_m << " m");
    const double side_m = 40.0, reflectance = 0.5, half = 0.5 * side_m;
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 24, 20, 0.5 * 24 / 150, 0.5);
    Eigen::Vector3d centre(distance_m, 0.0, 0.0);
    double roll_deg = 0.0;
    if (orientation == "vertical") {
        centre.y() = half;
    } else if (orientation == "horizontal") {
        centre.z() = -half;
    } else {
        roll_deg = 45.0;  // the square's edge at 45 deg, the plate below and to the left
        centre.y() = half / std::sqrt(2.0);
        centre.z() = -half / std::sqrt(2.0);
    }
    s.scene.objects.push_back(object_at(1, plate(side_m, reflectance),
                                        scene::Trajectory::fixed(scene::Pose{centre, scene::orientation_from_ypr_deg(0, 0, roll_deg)}),
                                        scene::ObjectClass::building));
    auto render = [&](int samples) {
        Scenario run = s;
        run.render.footprint_samples = samples;
        FrameRenderer renderer(run);
        std::map<int, double> energy;  // by raster cell
        for (const Return& r : renderer.render(0).returns) energy[r.row * 1000 + r.column] += r.intensity;
        return energy;
    };
    const auto adaptive = render(0), reference = render(4096);
    const double threshold_pe = threshold_photoelectrons(s);
    FrameRenderer geometry(s);
    int edge_beams = 0;
    for (int row = 0; row < geometry.raster().rows(); ++row) {
        for (int step = 0; step < geometry.raster().columns(); ++step) {
            const RasterBeam b = geometry.raster().beam(row, step);
            const int key = b.row * 1000 + b.column;
            const double cos_axis = std::cos(b.az_offset_rad) * std::cos(b.el_offset_rad);
            const double full = extended_target_photoelectrons(s.sensor, reflectance, cos_axis, distance_m / cos_axis);
            const double want = reference.contains(key) ? reference.at(key) : 0.0;
            const double got = adaptive.contains(key) ? adaptive.at(key) : 0.0;
            INFO("row " << b.row << " column " << b.column << " (beam " << b.row * geometry.raster().columns() + step << "): " << got / full << " of a full echo, reference " << want / full);
            if (want > 5.0 * threshold_pe) CHECK(got > 0.0);
            CHECK(std::abs(got - want) / full <= 0.02);
            edge_beams += want > 0.001 * full && want < 0.999 * full;
        }
    }
    CHECK(edge_beams > 20);
}
namespace {

/// The waveform peak (primary photo-electrons, as a return's intensity reads) of what a beam
/// aimed at raster offsets (az, el) sees of `plane` (through `point`, `normal`) where the sub-ray's
/// elevation is positive, integrated on a 601 x 601 grid over its footprint: at each cell the ray
/// meets the plane, its echo is the extended-target closed form at that range and incidence times
/// the cell's share of the Gaussian, and the pulses (of `pulse_sigma_m` in range) are summed on a
/// 1 mm grid of ranges. Also the range the receiver reads from that waveform.
std::pair<double, double> continuum_peak(const Sensor& sensor, double az, double el, const Eigen::Vector3d& point,
                                         const Eigen::Vector3d& normal, double reflectance, double pulse_sigma_m) {
    constexpr int kGrid = 601;
    const double w = 0.5 * sensor.transmitter.divergence_mrad * 1e-3, r_max = kTruncation * w;
    const Eigen::Matrix3d sensor_from_beam_axes = sensor_from_beam({}, az, el);
    std::vector<std::pair<double, double>> echoes;  // range, photo-electrons before normalising
    double total = 0.0;
    ladarsim::test::for_each_footprint_cell(kGrid, r_max, [&](double x, double y) {
        const double g = std::exp(-2.0 * (x * x + y * y) / (w * w));
        total += g;
        const Eigen::Vector3d d = sensor_from_beam_axes * Eigen::Vector3d(1.0, std::tan(x), std::tan(y)).normalized();
        if (d.z() <= 0.0) return;  // below the edge
        const double range = normal.dot(point) / normal.dot(d);
        echoes.emplace_back(range, g * extended_target_photoelectrons(sensor, reflectance, std::abs(normal.dot(d)), range));
    });
    if (echoes.empty()) return {0.0, 0.0};
    double lo = 1e300, hi = -1e300;
    for (const auto& [range, e] : echoes) {
        lo = std::min(lo, range);
        hi = std::max(hi, range);
    }
    std::vector<double> bins(static_cast<std::size_t>((hi - lo) / 1e-3) + 1, 0.0);
    for (const auto& [range, e] : echoes) bins[static_cast<std::size_t>((range - lo) / 1e-3)] += e / total;
    const int reach = static_cast<int>(6.0 * pulse_sigma_m / 1e-3);
    std::vector<double> kernel(static_cast<std::size_t>(2 * reach + 1));
    for (int k = -reach; k <= reach; ++k) kernel[static_cast<std::size_t>(k + reach)] = std::exp(-0.5 * std::pow(k * 1e-3 / pulse_sigma_m, 2));
    std::vector<double> wave;
    for (int b = -reach; b < static_cast<int>(bins.size()) + reach; ++b) {
        double sum = 0.0;
        for (int k = std::max(-reach, -b); k <= reach && b + k < static_cast<int>(bins.size()); ++k)
            sum += bins[static_cast<std::size_t>(b + k)] * kernel[static_cast<std::size_t>(reach - k)];
        wave.push_back(sum);
    }
    // The receiver times a return from its 50 % leading edge, plus half the pulse's width.
    const std::size_t peak = static_cast<std::size_t>(std::max_element(wave.begin(), wave.end()) - wave.begin());
    std::size_t edge = peak;
    while (edge > 0 && wave[edge - 1] >= 0.5 * wave[peak]) --edge;
    const double fwhm_m = pulse_sigma_m * std::sqrt(8.0 * std::log(2.0));
    return {wave[peak], lo + (static_cast<double>(edge) - reach) * 1e-3 + 0.5 * fwhm_m};
}

}  // namespace

TEST_CASE("a crest: the slope beyond an edge echoes as the footprint's continuum does", "[footprint][edges]") {
    // A wall whose straight top edge lies on the boresight's elevation, 500 m out, and behind it a
    // slope grazed at 5.7 deg, 1 km out, its range changing by 4.6 m over a footprint's radius:
    // a beam straddling the edge sees the slope above the edge only, where the beam is brightest,
    // so the slope's echo ends sharply there and peaks higher than its spread alone would say.
    // Each beam's return from the slope against its waveform's peak integrated here on a fine grid
    // (noise off): within 3 % where that exceeds 5x the threshold, none missing. Before, a side of
    // an edge that one cell fell on took one pulse stretched by its points' spread: on a crest seen
    // through the command line, 0.35x and 2.2x of 4096 sub-rays' in its two rows.
    const double grazing_deg = GENERATE(5.7, -5.7);  // the slope rising away, or falling away
    INFO("slope " << grazing_deg << " deg");
    const double reflectance = 0.3;
    Scenario s = closed_form_scenario();
    REQUIRE(s.sensor.transmitter.divergence_el_mrad == s.sensor.transmitter.divergence_mrad);
    set_raster(s.sensor, 4, 80, 0.5 * 4 / 150, 0.5);  // the edge at every quarter of a footprint's radius
    s.scene.objects.push_back(object_at(1, plate(100.0, 0.5),
                                        scene::Trajectory::fixed(scene::Pose{{500.0, 0.0, -50.0}, Eigen::Quaterniond::Identity()}),
                                        scene::ObjectClass::building));
    const Eigen::Quaterniond turn = scene::orientation_from_ypr_deg(0.0, 90.0 - grazing_deg, 0.0);
    const Eigen::Vector3d slope_point(1000.0, 0.0, 0.0), slope_normal = turn * Eigen::Vector3d::UnitX();
    s.scene.objects.push_back(object_at(2, plate(400.0, reflectance), scene::Trajectory::fixed(scene::Pose{slope_point, turn}),
                                        scene::ObjectClass::terrain));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);
    std::map<int, const Return*> slope_return;
    for (const Return& r : f.returns)
        if (r.object_id == 2) slope_return[r.row * 1000 + r.column] = &r;
    const double pulse_sigma_m = PulseShape::of(s.sensor.transmitter.pulse_width_ns * 1e-9).sigma_s * 0.5 * kSpeedOfLight_mps;
    const double threshold_pe = threshold_photoelectrons(s);
    const double r_max = kTruncation * 0.5 * s.sensor.transmitter.divergence_mrad * 1e-3;
    int straddling = 0;
    for (int row = 0; row < renderer.raster().rows(); ++row) {
        for (int step = 0; step < renderer.raster().columns(); ++step) {
            const RasterBeam b = renderer.raster().beam(row, step);
            if (std::abs(b.el_offset_rad) > r_max) continue;  // the edge outside
            const auto [want, want_range] = continuum_peak(s.sensor, b.az_offset_rad, b.el_offset_rad, slope_point, slope_normal,
                                                           reflectance, pulse_sigma_m);
            const auto it = slope_return.find(b.row * 1000 + b.column);
            const double got = it == slope_return.end() ? 0.0 : it->second->intensity;
            INFO("row " << b.row << " column " << b.column << ", elevation " << b.el_offset_rad / r_max << " r_max: " << got
                        << " photo-electrons against " << want << " at " << want_range << " m"
                        << (it == slope_return.end() ? std::string() : ", at " + std::to_string(it->second->range_m) + " m"));
            if (want < threshold_pe) continue;
            ++straddling;
            CHECK(got == Approx(want).epsilon(0.03));
            if (it != slope_return.end()) CHECK(std::abs(it->second->range_m - want_range) < pulse_sigma_m);
        }
    }
    CHECK(straddling >= 16);
}

namespace {

/// The default scenario's terrain without its drone, noise off, the gimbal at `elevation_deg`
/// straight ahead: level, footprints graze the ground from 700 m out and reach to the ridge at
/// 2 km (a footprint spans up to a kilometre of range), or pass above it; 2 deg down, plain ground.
Scenario horizon_scenario(double elevation_deg) {
    Scenario s = load_scenario(std::filesystem::path(LADARSIM_SOURCE_DIR) / "assets/scenarios/default.json");
    std::erase_if(s.scene.objects, [&](const scene::SceneObject& o) { return o.id == s.mount.cue_object_id; });
    s.mount.cue_object_id = 0;
    s.mount.gimbal_az_deg = 0.0;
    s.mount.gimbal_el_deg = elevation_deg;
    s.render.noise = false;
    return s;
}

}  // namespace

TEST_CASE("the horizon costs no more than a few times a look at the ground", "[footprint][horizon]") {
    // Work is counted in rays traced (deterministic); the speed ratio itself is the bench's
    // (hard_cases, "horizon").
    const Scenario level_scenario = horizon_scenario(0.0), down_scenario = horizon_scenario(-2.0);
    FrameRenderer level(level_scenario), down(down_scenario);
    std::uint64_t level_rays = 0, down_rays = 0;
    for (std::uint64_t frame = 0; frame < 3; ++frame) {
        level.render(frame);
        level_rays += level.rays_last_frame();
        down.render(frame);
        down_rays += down.rays_last_frame();
    }
    INFO("level " << level_rays << " rays, 2 deg down " << down_rays);
    CHECK(level_rays <= 8 * down_rays);
}

TEST_CASE("at the horizon each beam reports what 4096 sub-rays report", "[footprint][horizon]") {
    // Footprints straddling the ridge's crest: the ground in front of it, grazed over tens of
    // metres of range, and the ridge behind. A side of the crest that few cells fall on must keep
    // the range spread its points show, or its echo is as compact as its cells and is detected
    // where the whole footprint's stretched pulse is not (before: 32 such returns at 1,720 m in
    // the crest's row, the ridge's energy doubled).
    const Scenario adaptive_scenario = horizon_scenario(0.0);
    Scenario reference_scenario = horizon_scenario(0.0);
    reference_scenario.render.footprint_samples = 4096;
    FrameRenderer adaptive(adaptive_scenario), reference(reference_scenario);
    const Frame got = adaptive.render(0), want = reference.render(0);
    std::map<std::uint32_t, double> first_want;
    for (const Return& r : want.returns)
        if (r.return_index == 0) first_want[std::uint32_t{r.row} << 16 | r.column] = r.range_m;
    REQUIRE(want.returns.size() > 1000);
    CHECK(std::abs(double(got.returns.size()) - double(want.returns.size())) <= 0.005 * double(want.returns.size()));
    int far_off = 0;
    for (const Return& r : got.returns) {
        if (r.return_index != 0) continue;
        const auto it = first_want.find(std::uint32_t{r.row} << 16 | r.column);
        far_off += it == first_want.end() || std::abs(r.range_m - it->second) > 20.0;
    }
    INFO(got.returns.size() << " returns against " << want.returns.size());
    CHECK(far_off <= 2);
}

namespace {

/// A survey of rough ground as a recorded map: discs on a jittered 0.6 m grid (radius 0.42 m, the
/// half diagonal that closes the gaps), heights undulating by 0.3 m with 5 cm of roughness, each
/// disc's normal tilted by up to 8 deg (plane fits of a rough surface) and its reflectance drawn
/// in [0.1, 0.4]; seen from 60 m up, 4.3 deg down, so footprints graze it about 800 m out.
Scenario rough_survey_scenario(bool with_target = false) {
    Scenario s = closed_form_scenario();
    if (with_target) {
        // A 0.3 m plate (reflectance 0.3) 0.5 m over the ground on the middle beams' sight line.
        s.scene.objects.push_back(object_at(1, plate(0.3, 0.3), scene::Trajectory::fixed(scene::Pose{{790.0, 0.0, 1.25},
                                                                                                   Eigen::Quaterniond::Identity()})));
    }
    set_raster(s.sensor, 32, 20, 0.5 * 32.0 / 150.0, 0.5);
    s.mount.position_world = {0.0, 0.0, 60.0};
    s.mount.gimbal_el_deg = -4.29;
    std::mt19937 random(17);
    std::uniform_real_distribution<double> jitter(-0.15, 0.15), tilt(-0.14, 0.14), reflectance(0.1, 0.4);
    std::normal_distribution<double> rough(0.0, 0.05);
    scene::BackgroundMap map;
    map.source = "rough survey";
    for (double x = 700.0; x <= 900.0; x += 0.6) {
        for (double y = -4.0; y <= 4.0; y += 0.6) {
            const double px = x + jitter(random), py = y + jitter(random);
            map.points_world.emplace_back(px, py, 0.3 * std::sin(px / 7.0) * std::cos(py / 5.0) + rough(random));
            map.normals.push_back(Eigen::Vector3f(float(tilt(random)), float(tilt(random)), 1.0f).normalized());
            map.radii_m.push_back(0.42f);
            map.reflectance.push_back(float(reflectance(random)));
        }
    }
    s.scene.background = std::move(map);
    return s;
}

}  // namespace

namespace {

/// First-return range errors and the return count of renders against `want`, beam by beam,
/// averaged over renders with sixteen seeds: one seed's count of these 640 beams' returns scatters
/// by about 2.5 % (standard deviation), as much as the differences between ways of sampling that
/// these tests judge. (With eight, brute force's own count error moved from 5.2 % to 5.9 % on
/// adding eight more: a margin of one point was one standard error.)
struct MapErrors {
    double count_error = 0.0;  ///< |mean returns - reference returns| / reference returns
    double median_range_error_m = 0.0;  ///< mean over the renders
    double beams_found = 0.0;  ///< share of the reference's beams with a first return that report one (the least)
    double rays_per_beam = 0.0;
};

MapErrors map_errors(Scenario scenario, const Frame& want) {
    constexpr int kSeeds = 16;
    std::map<std::uint32_t, double> first_want;
    for (const Return& r : want.returns)
        if (r.return_index == 0) first_want[std::uint32_t{r.row} << 16 | r.column] = r.range_m;
    MapErrors e;
    e.beams_found = 1.0;
    double returns = 0.0;
    for (int k = 0; k < kSeeds; ++k) {
        FrameRenderer renderer(scenario);
        const Frame got = renderer.render(0);
        ++scenario.render.seed;
        std::vector<double> errors;
        for (const Return& r : got.returns) {
            if (r.return_index != 0) continue;
            const auto it = first_want.find(std::uint32_t{r.row} << 16 | r.column);
            if (it != first_want.end()) errors.push_back(std::abs(r.range_m - it->second));
        }
        returns += double(got.returns.size()) / kSeeds;
        e.rays_per_beam += double(renderer.rays_last_frame()) / renderer.raster().beam_count() / kSeeds;
        e.beams_found = std::min(e.beams_found, double(errors.size()) / double(first_want.size()));
        if (errors.empty()) continue;
        std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
        e.median_range_error_m += errors[errors.size() / 2] / kSeeds;
    }
    e.count_error = std::abs(returns - double(want.returns.size())) / double(want.returns.size());
    return e;
}

/// Brute force's sub-rays a footprint in these comparisons: what the shared sub-rays over a
/// recorded map took at the default tolerance before the scanline (1.5 x 256).
constexpr int lattice_budget() { return 384; }

}  // namespace

TEST_CASE("grazing a recorded map, the adaptive footprint does as well as brute force at its cost", "[footprint][map]") {
    // The discs of a map overlap and tilt at random, so neighbouring cells never agree, and the
    // refinement, judging energies only, reached its 256 sub-rays with returns worse placed than
    // 256 stratified ones (here +14.5 % returns and a median first-return error of 194 mm, against
    // +9.5 % and 51 mm; over Autzen, the bench's hard case, 38 mm against 8 mm). Such footprints
    // now take sub-rays of a lattice shared by the overlapping footprints of the frame's beams
    // (SubRayLattice), as many a footprint as brute force takes here, for a third of the rays: its
    // own stratified sub-rays placed first returns 48 mm from the reference's against brute
    // force's 38 mm. Now they are integrated along 32 lines (MapScanline). All against the map's
    // converged reference, a scanline of 256 lines: 4096 sub-rays, by their sampling noise in the
    // waveform, report 27 % more returns than it (1970 against 1548; 32 lines 1646), and were the
    // reference here until the scanline; brute force with other seeds.
    Scenario reference_scenario = rough_survey_scenario(), brute_scenario = rough_survey_scenario();
    reference_scenario.render.footprint_samples = 4096;
    reference_scenario.render.footprint_map_lines = 256;
    brute_scenario.render.footprint_samples = lattice_budget();
    brute_scenario.render.seed += 100;
    FrameRenderer reference(reference_scenario);
    const Frame want = reference.render(0);
    REQUIRE(want.returns.size() > 500);
    const MapErrors got = map_errors(rough_survey_scenario(), want), brute_force = map_errors(brute_scenario, want);
    const double rays_per_beam = got.rays_per_beam;
    INFO("adaptive: count error " << 100 * got.count_error << " %, median range error " << 1e3 * got.median_range_error_m << " mm, "
         << rays_per_beam << " rays/beam; " << lattice_budget() << " sub-rays: " << 100 * brute_force.count_error << " %, "
         << 1e3 * brute_force.median_range_error_m << " mm");
    CHECK(got.count_error <= brute_force.count_error + 0.01);
    CHECK(got.median_range_error_m <= 1.25 * brute_force.median_range_error_m);
    CHECK(got.beams_found >= 0.97);
    CHECK(rays_per_beam <= 0.5 * lattice_budget());
}

TEST_CASE("a small target over a recorded map: its echo as 4096 sub-rays weigh it, the map around it as brute force", "[footprint][map]") {
    // The rest of a target's footprints meets the map too: the lattice's sub-rays outside the
    // target's outline, carrying the rest's exact share (now along lines). Against the map's
    // converged reference (a scanline of 256 lines, 16 rays a line for the target).
    Scenario reference_scenario = rough_survey_scenario(true), brute_scenario = rough_survey_scenario(true);
    reference_scenario.render.footprint_samples = 4096;
    reference_scenario.render.footprint_map_lines = 256;
    brute_scenario.render.footprint_samples = lattice_budget();
    brute_scenario.render.seed += 100;
    const Scenario adaptive_scenario = rough_survey_scenario(true);
    FrameRenderer adaptive(adaptive_scenario), reference(reference_scenario);
    const Frame want = reference.render(0), got_frame = adaptive.render(0);
    const MapErrors got = map_errors(adaptive_scenario, want), brute_force = map_errors(brute_scenario, want);
    auto target_energy = [](const Frame& f) {
        double e = 0.0;
        for (const Return& r : f.returns) e += r.object_id == 1 ? r.intensity : 0.0;
        return e;
    };
    const double target_want = target_energy(want), target_got = target_energy(got_frame);
    // Every return of the beams that hold the target: the map beside it must carry the rest of
    // the beam, neither the target's share again nor less.
    std::map<std::uint32_t, double> beam_want, beam_got;
    for (const Return& r : want.returns)
        if (r.object_id == 1) beam_want[std::uint32_t{r.row} << 16 | r.column] = 0.0;
    for (const Return& r : want.returns)
        if (auto it = beam_want.find(std::uint32_t{r.row} << 16 | r.column); it != beam_want.end()) it->second += r.intensity;
    for (const Return& r : got_frame.returns)
        if (beam_want.contains(std::uint32_t{r.row} << 16 | r.column)) beam_got[std::uint32_t{r.row} << 16 | r.column] += r.intensity;
    double beams_want = 0.0, beams_error = 0.0;
    for (const auto& [key, e] : beam_want) {
        beams_want += e;
        beams_error += std::abs(beam_got[key] - e);
    }
    INFO("target energy " << target_got << " against " << target_want << "; its beams' energy off by " << 100 * beams_error / beams_want
         << " % (" << beam_want.size() << " beams); adaptive: count error " << 100 * got.count_error
         << " %, median range error " << 1e3 * got.median_range_error_m << " mm; " << lattice_budget() << " sub-rays: " << 100 * brute_force.count_error
         << " %, " << 1e3 * brute_force.median_range_error_m << " mm");
    REQUIRE(target_want > 0.0);
    CHECK(std::abs(target_got - target_want) <= 0.05 * target_want);
    CHECK(beams_error <= 0.05 * beams_want);
    CHECK(got.count_error <= brute_force.count_error + 0.01);
    CHECK(got.median_range_error_m <= 1.25 * brute_force.median_range_error_m);
}

TEST_CASE("sparse targets, one alone and one behind a flock: the strong returns two converged references agree on are found, and their energy is theirs", "[footprint][targets]") {
    // A quadcopter's arms and rotors fill a few per cent of a rectangle around it and the birds
    // 17 m in front of it, and a bird's wings (thin boxes) a few per cent of its box: an outline's
    // first cells can all miss such a target, and cells that agree on nothing settle. On a strip of
    // the paper's raster at 450 m (noise off), of the (beam, target) returns the references below
    // see at more than 5x the threshold, the adaptive footprints missed 88 of 200 without seeds
    // (rays at points of their surfaces); with them 1, the drone behind a bird, where it shows a
    // sliver (~0.06 % of the beam). Seen from 27 m below, as dataset 2's drone is (3.4 deg up).
    // The reference must itself be converged. 4096 sub-rays were not: a bright bird's fringe
    // (~14,500 thresholds per unit of the beam's energy, so 0.2 threshold a sub-ray at 65,536)
    // gave 6.5x the threshold at 4096 and 3.0x at 65,536. So two references of 65,536 sub-rays
    // (other seeds): a return both call strong is judged, and those strong in only one (within
    // their own scatter of the 5x cut) must be few.
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 32, 20, 0.5 * 32 / 150, 0.5);
    s.mount.gimbal_el_deg = std::atan2(27.0, 450.0) * 180.0 / M_PI;
    auto model = [](scene::Model m) { return std::make_shared<const scene::Model>(std::move(m)); };
    s.scene.objects.push_back(object_at(1, model(scene::make_quadcopter()), sliding({450.0, 0.0, 27.0}, {0.0, 0.5, 0.0})));
    const std::array<Eigen::Vector3d, 4> birds = {Eigen::Vector3d(433.0, 0.25, 26.1), Eigen::Vector3d(433.0, -0.2, 25.85),
                                                  Eigen::Vector3d(433.0, 0.1, 25.65), Eigen::Vector3d(450.0, 0.0, 28.2)};
    constexpr std::uint32_t kFirstBird = 20;
    for (std::size_t k = 0; k < birds.size(); ++k)
        s.scene.objects.push_back(object_at(static_cast<std::uint32_t>(kFirstBird + k), model(scene::make_bird(0.45)),
                                            sliding(birds[k], {-5.0, 0.0, 0.2}), scene::ObjectClass::bird));
    const auto is_bird = [&](std::uint32_t id) { return id >= kFirstBird && id < kFirstBird + birds.size(); };
    struct Seen {
        double energy_pe = 0.0;
        double range_m = 0.0;  ///< of its first return
    };
    using Returns = std::map<std::pair<int, std::uint32_t>, Seen>;  // by (raster cell, object)
    auto render = [&](int samples, std::uint64_t seed) {
        Scenario run = s;
        run.render.footprint_samples = samples;
        run.render.seed = seed;
        FrameRenderer renderer(run);
        Returns seen;
        for (const Return& r : renderer.render(0).returns) {
            auto [it, first] = seen.try_emplace({r.row * 1000 + r.column, r.object_id});
            if (first) it->second.range_m = r.range_m;
            it->second.energy_pe += r.intensity;
        }
        return seen;
    };
    constexpr int kReferenceSubRays = 65536;
    const Returns adaptive = render(0, 1), reference = render(kReferenceSubRays, 1), second = render(kReferenceSubRays, 2);
    const double threshold_pe = threshold_photoelectrons(s);
    // Echoes closer in range than the pulse's length make one pulse in the waveform, which the
    // receiver labels by the surface that gives most of it where it crosses the threshold: birds
    // flying together at one range (three here, 433 m out) make one return whose label is a near
    // tie between them. Such a return counts as found under any of those birds. The drone is
    // judged under its own label.
    const double pulse_length_m = 0.5 * kSpeedOfLight_mps * s.sensor.transmitter.pulse_width_ns * 1e-9;
    auto found = [&](const std::pair<int, std::uint32_t>& key, double range_m) {
        if (adaptive.contains(key)) return true;
        if (!is_bird(key.second)) return false;
        return std::any_of(adaptive.lower_bound({key.first, 0}), adaptive.upper_bound({key.first, kNoObject}), [&](const auto& other) {
            return is_bird(other.first.second) && std::abs(other.second.range_m - range_m) < pulse_length_m;
        });
    };
    auto strong_in = [&](const Returns& x, const std::pair<int, std::uint32_t>& key) {
        const auto it = x.find(key);
        return it != x.end() && it->second.energy_pe > 5.0 * threshold_pe;
    };
    std::set<std::pair<int, std::uint32_t>> keys;
    for (const Returns* x : {&reference, &second})
        for (const auto& [key, seen] : *x) keys.insert(key);
    int strong = 0, one_only = 0, missing = 0;
    std::set<std::uint32_t> targets;
    for (const auto& key : keys) {
        const bool a = strong_in(reference, key), b = strong_in(second, key);
        one_only += a != b;
        if (!a || !b) continue;
        ++strong;
        targets.insert(key.second);
        if (found(key, reference.at(key).range_m)) continue;
        ++missing;
        UNSCOPED_INFO("missing: beam " << key.first << ", object " << key.second << ", " << reference.at(key).energy_pe << " photo-electrons");
    }
    // Their energy in all: the outlines' refinement once measured each cell by the sub-ray that
    // chose it, so a sparse target's hit, splitting its cell, kept half its weight where a miss
    // that settled kept all of its own: over 12 renders (seeds) -10.8 % of the reference's on
    // average. Every final cell now takes a fresh sub-ray: over 25 seeds +1.5 % (one render
    // scatters by 4.9 %, its mean over 12 so by 1.4 %; the second reference +0.1 %).
    auto total = [](const Returns& x) {
        double sum = 0.0;
        for (const auto& [key, seen] : x) sum += seen.energy_pe;
        return sum;
    };
    constexpr int kRenders = 12;
    double in_all = 0.0;
    for (int seed = 1; seed <= kRenders; ++seed) in_all += (seed == 1 ? total(adaptive) : total(render(0, seed))) / total(reference) / kRenders;
    in_all -= 1.0;
    const double floor = total(second) / total(reference) - 1.0;
    INFO(strong << " strong (beam, target) returns in both references, " << one_only << " in one only, " << missing << " missing; energy in all "
                << in_all << " (" << kRenders << " renders; second reference " << floor << ")");
    REQUIRE(targets.size() == 5);  // the drone and every bird
    CHECK(one_only <= strong / 50);
    CHECK(missing <= strong / 50);
    CHECK(std::abs(in_all) < 0.05);
}

TEST_CASE("a bright lone drone: its energy as 4096 sub-rays weigh it, in all and beam by beam", "[footprint][targets]") {
    // A flying quadcopter at 300 m on a strip of the paper's raster (noise off), bright enough that
    // an outline refined cell by cell ran to its budget on the arms' and rotors' inner edges and
    // misweighed them: its energy in all -2.1 % of the reference's, a strong beam's off by 15.9 % on
    // average where a second reference (another seed) is off by 9.6 % (11.6 % with a third seed:
    // a drone's thin parts scatter even 4096 sub-rays). Sampled as one stratified grid of that
    // budget: -0.4 % and 10.3 %. The beams of a line now share one stratified lattice over it
    // (TargetLattice): a strong beam's error 9.6 %, and one render's total scatters by about 1 %
    // between seeds (the ~15 beams of a line weigh the same few hundred sub-rays; this one +1.1 %),
    // so the total's bias is judged on the mean of eight renders: -0.1 %.
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 48, 20, 0.5 * 48 / 150, 0.5);
    auto model = std::make_shared<const scene::Model>(scene::make_quadcopter());
    s.scene.objects.push_back(object_at(1, model, sliding({300.0, 0.0, 0.0}, {0.0, 8.0, 0.0})));
    auto render = [&](int samples, std::uint64_t seed) {
        Scenario run = s;
        run.render.footprint_samples = samples;
        run.render.seed = seed;
        FrameRenderer renderer(run);
        std::map<int, double> energy;  // by frame and raster cell
        for (std::uint64_t frame = 0; frame < 3; ++frame)
            for (const Return& r : renderer.render(frame).returns)
                if (r.object_id == 1) energy[int(frame) * 100000 + r.row * 1000 + r.column] += r.intensity;
        return energy;
    };
    const auto adaptive = render(0, 1), reference = render(4096, 2), second = render(4096, 3);
    constexpr std::array<std::uint64_t, 8> kSeeds = {1, 4, 5, 6, 7, 8, 9, 10};
    const double threshold_pe = threshold_photoelectrons(s);
    struct Against {
        double total = 0.0, abs_error = 0.0;  ///< energy in all; summed relative error of the strong beams
    };
    int strong = 0;
    auto against = [&](const std::map<int, double>& x) {
        Against a;
        for (const auto& [key, e] : x) a.total += e;
        for (const auto& [key, e] : reference) {
            if (e <= 5.0 * threshold_pe) continue;
            const auto it = x.find(key);
            a.abs_error += std::abs((it == x.end() ? 0.0 : it->second) - e) / e;
        }
        return a;
    };
    for (const auto& [key, e] : reference) strong += e > 5.0 * threshold_pe;
    double total_reference = 0.0;
    for (const auto& [key, e] : reference) total_reference += e;
    const Against a = against(adaptive), floor = against(second);
    double mean_total = 0.0;
    for (const std::uint64_t seed : kSeeds) mean_total += (seed == 1 ? a : against(render(0, seed))).total / kSeeds.size();
    INFO(strong << " strong beams; in all " << mean_total / total_reference - 1.0 << " (one render " << a.total / total_reference - 1.0
                << ", second reference " << floor.total / total_reference - 1.0 << "); a strong beam's mean |error| "
                << a.abs_error / strong << " (second reference " << floor.abs_error / strong << ")");
    REQUIRE(strong > 40);
    CHECK(std::abs(mean_total / total_reference - 1.0) < 0.01);
    CHECK(a.abs_error <= 1.25 * floor.abs_error);
}

TEST_CASE("gather_surfaces orders echoes by object and exact range, stably, also below float resolution", "[footprint]") {
    // The sort takes the range as a float for its radix passes and settles what rounding made equal
    // by an insertion pass over the exact ranges: against std::stable_sort on the exact keys, for a
    // beam's few echoes and a map footprint's hundreds, with ranges 1e-7 m apart at 1 km (the
    // float's step there is 6e-5 m), repeated keys, and two objects interleaved.
    for (const int n : {5, 63, 64, 500}) {
        std::vector<SurfaceEcho> echoes;
        std::mt19937 random(static_cast<unsigned>(n));
        for (int i = 0; i < n; ++i) {
            SurfaceEcho e{};
            e.point_world.setZero();
            e.normal_world.setZero();
            e.range_m = 1000.0 + 1e-7 * static_cast<double>(random() % 13) + (random() % 5 == 0 ? 0.5 : 0.0);
            e.weight = 1.0 / n;
            e.energy_j = static_cast<double>(i);  // the echo's original place, to check stability
            e.object_id = 1 + static_cast<std::uint32_t>(random() % 2);
            echoes.push_back(e);
        }
        std::vector<SurfaceEcho> expected = echoes;
        std::stable_sort(expected.begin(), expected.end(), [](const SurfaceEcho& a, const SurfaceEcho& b) {
            return a.object_id != b.object_id ? a.object_id < b.object_id : a.range_m < b.range_m;
        });
        gather_surfaces(echoes, 0.1);
        REQUIRE(echoes.size() == expected.size());
        for (std::size_t i = 0; i < echoes.size(); ++i) {
            INFO(n << " echoes, place " << i);
            CHECK(echoes[i].object_id == expected[i].object_id);
            CHECK(echoes[i].range_m == expected[i].range_m);
            CHECK(echoes[i].energy_j == expected[i].energy_j);
        }
    }
}

