#pragma once
// The sensor as data: scan geometry, timing, footprint, gimbal, transmitter, receiver and detector.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/json_fields.h"

namespace ladarsim::sensor_model {

enum class GalvoSweep {
    sawtooth,  ///< every line sweeps in +azimuth order, one line per galvo period (fly-back not modelled)
    triangle,  ///< two lines per galvo period, alternating direction
};

std::string to_string(GalvoSweep sweep);

/// How the beams of a frame are fired.
enum class ScanPattern {
    galvo,     ///< line by line: a galvanometer sweeps each elevation row across the field (the paper's LADAR)
    spinning,  ///< column by column: a spinning head fires all its channels at each azimuth step (Velodyne)
};

std::string to_string(ScanPattern scan);

/// Which of a beam's detected returns the sensor reports.
enum class ReportedReturns { all, first, last, strongest, first_and_last };

std::string to_string(ReportedReturns r);

struct SensorConfig {
    std::string preset = "paper_ladar";
    double wavelength_nm = 1560.0;
    double field_az_deg = 0.5;       ///< full field of the raster in azimuth
    double field_el_deg = 0.5;
    int beams_az = 150;              ///< beams per line
    int beams_el = 20;               ///< lines per frame
    ScanPattern scan = ScanPattern::galvo;
    double divergence_mrad = 0.62;   ///< full angle at the 1/e^2 irradiance radius, in azimuth
    double divergence_el_mrad = 0.62;///< the same in elevation (elliptical beams)
    double galvo_rate_hz = 1000.0;
    GalvoSweep sweep = GalvoSweep::sawtooth;
    double frame_rate_hz = 20.0;
    double pulse_rate_hz = 1.0e6;    ///< laser repetition rate (several pulses per beam position)
    double max_range_m = 3000.0;     ///< returns beyond are not reported

    double gimbal_az_limit_deg = 175.0;  ///< +- about the mount's x axis: 350 deg in all
    double gimbal_el_min_deg = -30.0;    ///< 120 deg in all
    double gimbal_el_max_deg = 90.0;
    double gimbal_slew_rate_dps = 16.0;

    /// 0: adaptive footprints to `footprint_tolerance`; N > 0: N stratified sub-rays per beam
    /// (brute force, the reference the adaptive integration is checked against).
    int footprint_samples = 0;
    /// Relative error allowed on each object's echo energy per beam (adaptive footprints).
    double footprint_tolerance = 0.05;
    double footprint_truncation = 1.5;   ///< sub-rays lie within this many 1/e^2 radii
    double return_gap_m = 0.15;          ///< surfaces closer than this along a beam merge (c * 1 ns / 2)

    // Transmitter. The paper's 700 kW x 1 ns x 1 MHz is 700 W of average power; kept as given.
    double peak_power_w = 700e3;
    double pulse_width_ns = 1.0;         ///< full width at half maximum of a Gaussian pulse
    /// Several pulses in the air at once: returns beyond c / (2 PRF) arrive in a later pulse's
    /// range gate and are reported at their range modulo the unambiguous range.
    bool range_folding = true;

    // Receiver. The paper gives no aperture or optics; these are estimates for a 1560 nm
    // InGaAs APD receiver, in the data so a scenario can override them.
    double aperture_diameter_m = 0.05;
    double optics_efficiency = 0.5;      ///< transmit x receive optics and filter transmission
    double receiver_fov_mrad = 1.0;      ///< full angle seen by the detector (for solar background)
    double filter_width_nm = 1.0;        ///< optical band-pass around the wavelength
    double responsivity_a_per_w = 0.9;   ///< at unity gain
    double apd_gain = 10.0;
    double excess_noise_factor = 5.5;    ///< F at this gain
    double bandwidth_hz = 500e6;
    double dark_current_a = 5e-9;        ///< primary (multiplied) bulk dark current
    double load_resistance_ohm = 5000.0; ///< transimpedance seen by the thermal noise
    double temperature_k = 300.0;
    double saturation_current_a = 2e-3;  ///< output current at which the receiver clips
    /// Target rate of noise-only threshold crossings; it sets the detection threshold.
    double false_alarm_rate_hz = 75.0;
    ReportedReturns reported_returns = ReportedReturns::all;

    /// Throws InputError(file, "sensor.<field>", ...) for values no sensor can have.
    void validate(const std::string& file) const;

    /// Derived quantities people check the paper's numbers with.
    double line_duration_s() const;
    double frame_scan_duration_s() const;  ///< time the galvo needs for all lines of a frame
    double beam_dwell_s() const;           ///< time per beam position
    double pulses_per_beam() const;
    double unambiguous_range_m() const;    ///< c / (2 * pulse rate)
    double beam_pitch_az_mrad() const;
    double beam_pitch_el_mrad() const;
    double beams_per_second() const;       ///< beams per frame * frame rate
    double pulse_energy_j() const;         ///< peak power x FWHM x sqrt(pi / (4 ln 2)) (Gaussian)
    double average_power_w() const;        ///< pulse energy x pulse rate
    double aperture_area_m2() const;
    /// Time a beam's receiver listens for one pulse: one pulse period when ranges fold, else
    /// the time of flight to max_range_m.
    double range_gate_s() const;
};

/// Names of the built-in presets.
std::vector<std::string> sensor_presets();
/// A preset by name; throws std::invalid_argument for an unknown one.
SensorConfig sensor_preset(const std::string& name);

/// Reads the sensor parameters of a scenario's "sensor" object: "preset" first, then any
/// parameter overriding it. Keys it does not know are left unused (the caller owns the object).
SensorConfig read_sensor_config(JsonFields& sensor);

/// Every parameter and the derived quantities, for the manifest and `ladarsim sensor show`.
nlohmann::json to_json(const SensorConfig& config);

}  // namespace ladarsim::sensor_model
