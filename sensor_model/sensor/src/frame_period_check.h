#pragma once
// Shared by the scan patterns' readers: a frame's scan must fit in its frame period.
#include <string>

#include "ladarsim/sensor_model/sensor/scan_pattern.h"

namespace ladarsim::sensor_model {

inline void check_frame_period(const ScanPattern& scan, JsonFields& fields) {
    const double period_s = 1.0 / scan.frame_rate_hz();
    if (scan.frame_scan_duration_s() > period_s * (1.0 + 1e-12)) {
        fields.fail("frame_rate_hz", "a frame needs " + std::to_string(scan.frame_scan_duration_s() * 1e3) +
                                         " ms of scanning, longer than the frame period of " +
                                         std::to_string(1e3 * period_s) + " ms");
    }
}

}  // namespace ladarsim::sensor_model
