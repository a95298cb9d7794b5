#pragma once
// The detector and its electronics: gain, noise, threshold, saturation, range gate, and which
// returns the sensor reports.
#include <string>

#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

/// Which of a beam's detected returns the sensor reports.
enum class ReportedReturns { all, first, last, strongest, first_and_last };

std::string to_string(ReportedReturns r);

struct Receiver {
    double responsivity_a_per_w = 0.0;   ///< at unity gain
    double apd_gain = 0.0;
    double excess_noise_factor = 0.0;    ///< F at this gain
    double bandwidth_hz = 0.0;
    double dark_current_a = 0.0;        ///< primary (multiplied) bulk dark current
    double load_resistance_ohm = 0.0; ///< transimpedance seen by the thermal noise
    double temperature_k = 0.0;
    double saturation_current_a = 0.0;  ///< output current at which the receiver clips
    /// Target rate of noise-only threshold crossings; it sets the detection threshold.
    double false_alarm_rate_hz = 0.0;
    double max_range_m = 0.0;         ///< returns beyond are not reported
    /// Returns from closer than this are not reported: the receiver is blind while the outgoing
    /// pulse's own flash (scattered inside the optics) fades, or where the transmitted beam has not
    /// yet entered the receiver's field. Real sensors all have one; 0 (the default) for none.
    double min_range_m = 0.0;
    /// Several pulses in the air at once: returns beyond c / (2 PRF) arrive in a later pulse's
    /// range gate and are reported at their range modulo the unambiguous range.
    bool range_folding = false;
    double return_gap_m = 0.0;          ///< surfaces closer than this along a beam merge (c * 1 ns / 2)
    ReportedReturns reported_returns = ReportedReturns::all;

    static Receiver read(JsonFields& receiver);
    nlohmann::json to_json() const;
};

}  // namespace ladarsim::sensor_model
