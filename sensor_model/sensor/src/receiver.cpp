#include "ladarsim/sensor_model/sensor/receiver.h"

#include <algorithm>
#include <vector>

#include "ladarsim/core/input_error.h"

namespace ladarsim::sensor_model {

namespace {
const std::vector<std::string> kReportedReturnsNames = {"all", "first", "last", "strongest", "first_and_last"};
}

std::string to_string(ReportedReturns r) { return kReportedReturnsNames[static_cast<std::size_t>(r)]; }

Receiver Receiver::read(JsonFields& r) {
    Receiver x;
    x.responsivity_a_per_w = r.number("responsivity_a_per_w", 1e-3, 10.0);
    x.apd_gain = r.number("apd_gain", 1.0, 1e4);
    x.excess_noise_factor = r.number("excess_noise_factor", 1.0, 1e3);
    x.bandwidth_hz = r.number("bandwidth_hz", 1e3, 1e11);
    x.dark_current_a = r.number("dark_current_a", 0.0, 1e-3);
    x.load_resistance_ohm = r.number("load_resistance_ohm", 1e-3, 1e9);
    x.temperature_k = r.number("temperature_k", 1.0, 1000.0);
    x.saturation_current_a = r.number("saturation_current_a", 1e-9, 1e3);
    x.false_alarm_rate_hz = r.number("false_alarm_rate_hz", 1e-9, 1e9);
    x.max_range_m = r.number("max_range_m", 1.0, 1e6);
    x.min_range_m = r.number("min_range_m", 0.0, 1e4, 0.0);
    if (x.min_range_m >= x.max_range_m)
        throw InputError(r.file(), r.path_of("min_range_m"), "must be below max_range_m (" + std::to_string(x.max_range_m) + ")");
    x.range_folding = r.boolean("range_folding", false);
    x.return_gap_m = r.number("return_gap_m", 0.0, 1e3);
    const std::string reported = r.choice("reported_returns", kReportedReturnsNames, "all");
    x.reported_returns = static_cast<ReportedReturns>(
        std::find(kReportedReturnsNames.begin(), kReportedReturnsNames.end(), reported) - kReportedReturnsNames.begin());
    return x;
}

nlohmann::json Receiver::to_json() const {
    return {{"responsivity_a_per_w", responsivity_a_per_w},
            {"apd_gain", apd_gain},
            {"excess_noise_factor", excess_noise_factor},
            {"bandwidth_hz", bandwidth_hz},
            {"dark_current_a", dark_current_a},
            {"load_resistance_ohm", load_resistance_ohm},
            {"temperature_k", temperature_k},
            {"saturation_current_a", saturation_current_a},
            {"false_alarm_rate_hz", false_alarm_rate_hz},
            {"max_range_m", max_range_m},
            {"min_range_m", min_range_m},
            {"range_folding", range_folding},
            {"return_gap_m", return_gap_m},
            {"reported_returns", to_string(reported_returns)}};
}

}  // namespace ladarsim::sensor_model
