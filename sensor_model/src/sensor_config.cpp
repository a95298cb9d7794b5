#include "ladarsim/sensor_model/sensor_config.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ladarsim/dataset/input_error.h"
#include "ladarsim/sensor_model/physical_constants.h"

namespace ladarsim::sensor_model {

std::string to_string(GalvoSweep sweep) { return sweep == GalvoSweep::sawtooth ? "sawtooth" : "triangle"; }

namespace {
const std::vector<std::string> kReportedReturnsNames = {"all", "first", "last", "strongest", "first_and_last"};
}

std::string to_string(ScanPattern scan) { return scan == ScanPattern::galvo ? "galvo" : "spinning"; }

std::string to_string(ReportedReturns r) { return kReportedReturnsNames[static_cast<std::size_t>(r)]; }

double SensorConfig::line_duration_s() const {
    if (scan == ScanPattern::spinning) return 1.0 / frame_rate_hz;  // one revolution holds every row
    return sweep == GalvoSweep::sawtooth ? 1.0 / galvo_rate_hz : 0.5 / galvo_rate_hz;
}
double SensorConfig::frame_scan_duration_s() const {
    return scan == ScanPattern::spinning ? 1.0 / frame_rate_hz : beams_el * line_duration_s();
}
double SensorConfig::beam_dwell_s() const {
    // A spinning head fires its channels one after another within each azimuth step.
    return scan == ScanPattern::spinning ? line_duration_s() / (double(beams_az) * beams_el) : line_duration_s() / beams_az;
}
double SensorConfig::pulses_per_beam() const { return pulse_rate_hz * beam_dwell_s(); }
double SensorConfig::unambiguous_range_m() const { return kSpeedOfLight_mps / (2.0 * pulse_rate_hz); }
double SensorConfig::beam_pitch_az_mrad() const { return field_az_deg * std::numbers::pi / 180.0 / beams_az * 1e3; }
double SensorConfig::beam_pitch_el_mrad() const { return field_el_deg * std::numbers::pi / 180.0 / beams_el * 1e3; }
double SensorConfig::beams_per_second() const { return double(beams_az) * beams_el * frame_rate_hz; }
double SensorConfig::pulse_energy_j() const {
    return peak_power_w * pulse_width_ns * 1e-9 * std::sqrt(std::numbers::pi / (4.0 * std::numbers::ln2));
}
double SensorConfig::average_power_w() const { return pulse_energy_j() * pulse_rate_hz; }
double SensorConfig::aperture_area_m2() const { return std::numbers::pi / 4.0 * aperture_diameter_m * aperture_diameter_m; }
double SensorConfig::range_gate_s() const {
    return range_folding ? 1.0 / pulse_rate_hz : 2.0 * max_range_m / kSpeedOfLight_mps;
}

void SensorConfig::validate(const std::string& file) const {
    auto fail = [&](const char* field, const std::string& problem) {
        throw InputError(file, std::string("sensor.") + field, problem);
    };
    if (frame_scan_duration_s() > 1.0 / frame_rate_hz * (1.0 + 1e-12)) {
        fail("frame_rate_hz", "a frame needs " + std::to_string(frame_scan_duration_s() * 1e3) +
                                  " ms of galvo sweep, longer than the frame period of " +
                                  std::to_string(1e3 / frame_rate_hz) + " ms");
    }
    if (gimbal_el_min_deg >= gimbal_el_max_deg) fail("gimbal_el_min_deg", "must be below gimbal_el_max_deg");
    if (scan == ScanPattern::galvo && field_az_deg > 180.0) fail("field_az_deg", "a galvo field must be at most 180 deg");
    if (field_el_deg > 180.0) fail("field_el_deg", "must be at most 180 deg");
}

std::vector<std::string> sensor_presets() { return {"paper_ladar", "velodyne_vlp16"}; }

SensorConfig sensor_preset(const std::string& name) {
    if (name == "paper_ladar") return SensorConfig{};
    if (name == "velodyne_vlp16") {
        // The sensor the paper measured a real drone with. Geometry from Velodyne's VLP-16 manual:
        // 16 channels 2 deg apart over +-15 deg, 0.1-0.4 deg azimuth steps at 5-20 Hz (0.2 deg at
        // 10 Hz here), 903 nm, beam divergence 3.0 mrad horizontal x 1.5 mrad vertical, 100 m range,
        // strongest return. Velodyne publishes no radiometry: the transmitter and Si APD receiver
        // values below are estimates for a class 1 905 nm pulsed diode (tens of W, a few ns).
        SensorConfig c;
        c.preset = name;
        c.wavelength_nm = 903.0;
        c.scan = ScanPattern::spinning;
        c.field_az_deg = 360.0;
        c.field_el_deg = 32.0;
        c.beams_az = 1800;
        c.beams_el = 16;
        c.divergence_mrad = 3.0;
        c.divergence_el_mrad = 1.5;
        c.frame_rate_hz = 10.0;
        c.pulse_rate_hz = 288e3;  // 16 x 1800 x 10: one pulse per channel and step
        c.max_range_m = 100.0;
        c.gimbal_az_limit_deg = 0.0;
        c.gimbal_el_min_deg = -1e-9;
        c.gimbal_el_max_deg = 0.0;
        c.gimbal_slew_rate_dps = 0.0;
        c.peak_power_w = 30.0;
        c.pulse_width_ns = 6.0;
        c.range_folding = false;
        c.aperture_diameter_m = 0.025;
        c.optics_efficiency = 0.5;
        c.receiver_fov_mrad = 4.0;
        c.filter_width_nm = 20.0;
        c.responsivity_a_per_w = 0.6;
        c.apd_gain = 100.0;
        c.excess_noise_factor = 4.0;
        c.bandwidth_hz = 100e6;
        c.dark_current_a = 1e-10;
        c.load_resistance_ohm = 10e3;
        c.false_alarm_rate_hz = 10.0;
        c.reported_returns = ReportedReturns::strongest;
        return c;
    }
    throw std::invalid_argument("unknown sensor preset \"" + name + "\"");
}

SensorConfig read_sensor_config(JsonFields& sensor) {
    SensorConfig c = sensor_preset(sensor.choice("preset", sensor_presets(), "paper_ladar"));
    c.wavelength_nm = sensor.number("wavelength_nm", 200.0, 20000.0, c.wavelength_nm);
    const std::string scan = sensor.choice("scan", {"galvo", "spinning"}, to_string(c.scan));
    c.scan = scan == "galvo" ? ScanPattern::galvo : ScanPattern::spinning;
    c.field_az_deg = sensor.number("field_az_deg", 1e-4, 360.0, c.field_az_deg);
    c.field_el_deg = sensor.number("field_el_deg", 1e-4, 360.0, c.field_el_deg);
    c.beams_az = static_cast<int>(sensor.integer("beams_az", 1, 65535, c.beams_az));
    c.beams_el = static_cast<int>(sensor.integer("beams_el", 1, 65535, c.beams_el));
    c.divergence_mrad = sensor.number("divergence_mrad", 1e-4, 100.0, c.divergence_mrad);
    // One divergence given for a round beam sets both axes.
    c.divergence_el_mrad = sensor.number("divergence_el_mrad", 1e-4, 100.0,
                                         sensor.has("divergence_mrad") ? c.divergence_mrad : c.divergence_el_mrad);
    c.galvo_rate_hz = sensor.number("galvo_rate_hz", 1e-3, 1e7, c.galvo_rate_hz);
    const std::string sweep = sensor.choice("sweep", {"sawtooth", "triangle"}, to_string(c.sweep));
    c.sweep = sweep == "sawtooth" ? GalvoSweep::sawtooth : GalvoSweep::triangle;
    c.frame_rate_hz = sensor.number("frame_rate_hz", 1e-3, 1e4, c.frame_rate_hz);
    c.pulse_rate_hz = sensor.number("pulse_rate_hz", 1.0, 1e9, c.pulse_rate_hz);
    c.max_range_m = sensor.number("max_range_m", 1.0, 1e6, c.max_range_m);
    c.gimbal_az_limit_deg = sensor.number("gimbal_az_limit_deg", 0.0, 180.0, c.gimbal_az_limit_deg);
    c.gimbal_el_min_deg = sensor.number("gimbal_el_min_deg", -90.0, 90.0, c.gimbal_el_min_deg);
    c.gimbal_el_max_deg = sensor.number("gimbal_el_max_deg", -90.0, 90.0, c.gimbal_el_max_deg);
    c.gimbal_slew_rate_dps = sensor.number("gimbal_slew_rate_dps", 0.0, 1e4, c.gimbal_slew_rate_dps);
    c.footprint_samples = static_cast<int>(sensor.integer("footprint_samples", 0, 4096, c.footprint_samples));
    c.footprint_tolerance = sensor.number("footprint_tolerance", 1e-4, 1.0, c.footprint_tolerance);
    c.footprint_truncation = sensor.number("footprint_truncation", 0.1, 4.0, c.footprint_truncation);
    c.return_gap_m = sensor.number("return_gap_m", 0.0, 1e3, c.return_gap_m);
    c.peak_power_w = sensor.number("peak_power_w", 1e-6, 1e12, c.peak_power_w);
    c.pulse_width_ns = sensor.number("pulse_width_ns", 0.01, 1e6, c.pulse_width_ns);
    c.range_folding = sensor.boolean("range_folding", c.range_folding);
    c.aperture_diameter_m = sensor.number("aperture_diameter_m", 1e-4, 10.0, c.aperture_diameter_m);
    c.optics_efficiency = sensor.number("optics_efficiency", 1e-6, 1.0, c.optics_efficiency);
    c.receiver_fov_mrad = sensor.number("receiver_fov_mrad", 1e-3, 1e3, c.receiver_fov_mrad);
    c.filter_width_nm = sensor.number("filter_width_nm", 1e-3, 1e3, c.filter_width_nm);
    c.responsivity_a_per_w = sensor.number("responsivity_a_per_w", 1e-3, 10.0, c.responsivity_a_per_w);
    c.apd_gain = sensor.number("apd_gain", 1.0, 1e4, c.apd_gain);
    c.excess_noise_factor = sensor.number("excess_noise_factor", 1.0, 1e3, c.excess_noise_factor);
    c.bandwidth_hz = sensor.number("bandwidth_hz", 1e3, 1e11, c.bandwidth_hz);
    c.dark_current_a = sensor.number("dark_current_a", 0.0, 1e-3, c.dark_current_a);
    c.load_resistance_ohm = sensor.number("load_resistance_ohm", 1e-3, 1e9, c.load_resistance_ohm);
    c.temperature_k = sensor.number("temperature_k", 1.0, 1000.0, c.temperature_k);
    c.saturation_current_a = sensor.number("saturation_current_a", 1e-9, 1e3, c.saturation_current_a);
    c.false_alarm_rate_hz = sensor.number("false_alarm_rate_hz", 1e-9, 1e9, c.false_alarm_rate_hz);
    const std::string reported = sensor.choice("reported_returns", kReportedReturnsNames, to_string(c.reported_returns));
    c.reported_returns = static_cast<ReportedReturns>(
        std::find(kReportedReturnsNames.begin(), kReportedReturnsNames.end(), reported) - kReportedReturnsNames.begin());
    c.validate(sensor.file());
    return c;
}

nlohmann::json to_json(const SensorConfig& c) {
    return {
        {"preset", c.preset},
        {"wavelength_nm", c.wavelength_nm},
        {"field_az_deg", c.field_az_deg},
        {"field_el_deg", c.field_el_deg},
        {"beams_az", c.beams_az},
        {"beams_el", c.beams_el},
        {"scan", to_string(c.scan)},
        {"divergence_mrad", c.divergence_mrad},
        {"divergence_el_mrad", c.divergence_el_mrad},
        {"galvo_rate_hz", c.galvo_rate_hz},
        {"sweep", to_string(c.sweep)},
        {"frame_rate_hz", c.frame_rate_hz},
        {"pulse_rate_hz", c.pulse_rate_hz},
        {"max_range_m", c.max_range_m},
        {"gimbal_az_limit_deg", c.gimbal_az_limit_deg},
        {"gimbal_el_min_deg", c.gimbal_el_min_deg},
        {"gimbal_el_max_deg", c.gimbal_el_max_deg},
        {"gimbal_slew_rate_dps", c.gimbal_slew_rate_dps},
        {"footprint_samples", c.footprint_samples},
        {"footprint_tolerance", c.footprint_tolerance},
        {"footprint_truncation", c.footprint_truncation},
        {"return_gap_m", c.return_gap_m},
        {"peak_power_w", c.peak_power_w},
        {"pulse_width_ns", c.pulse_width_ns},
        {"range_folding", c.range_folding},
        {"aperture_diameter_m", c.aperture_diameter_m},
        {"optics_efficiency", c.optics_efficiency},
        {"receiver_fov_mrad", c.receiver_fov_mrad},
        {"filter_width_nm", c.filter_width_nm},
        {"responsivity_a_per_w", c.responsivity_a_per_w},
        {"apd_gain", c.apd_gain},
        {"excess_noise_factor", c.excess_noise_factor},
        {"bandwidth_hz", c.bandwidth_hz},
        {"dark_current_a", c.dark_current_a},
        {"load_resistance_ohm", c.load_resistance_ohm},
        {"temperature_k", c.temperature_k},
        {"saturation_current_a", c.saturation_current_a},
        {"false_alarm_rate_hz", c.false_alarm_rate_hz},
        {"reported_returns", to_string(c.reported_returns)},
        // The raster again, in the shape readers of a dataset take it from (dataset/manifest.h);
        // divergence_mrad there is the wider axis.
        {"derived",
         {{"beams_az", c.beams_az},
          {"beams_el", c.beams_el},
          {"field_az_deg", c.field_az_deg},
          {"field_el_deg", c.field_el_deg},
          {"divergence_mrad", std::max(c.divergence_mrad, c.divergence_el_mrad)},
          {"line_duration_s", c.line_duration_s()},
          {"frame_scan_duration_s", c.frame_scan_duration_s()},
          {"beam_dwell_s", c.beam_dwell_s()},
          {"pulses_per_beam", c.pulses_per_beam()},
          {"unambiguous_range_m", c.unambiguous_range_m()},
          {"beam_pitch_az_mrad", c.beam_pitch_az_mrad()},
          {"beam_pitch_el_mrad", c.beam_pitch_el_mrad()},
          {"beams_per_second", c.beams_per_second()},
          {"pulse_energy_j", c.pulse_energy_j()},
          {"average_power_w", c.average_power_w()},
          {"range_gate_s", c.range_gate_s()}}},
    };
}

}  // namespace ladarsim::sensor_model
