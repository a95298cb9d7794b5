#pragma once
// The two Ouster captures in the shared data, as the decoding and re-rendering tests use them; a
// test whose captures are missing is skipped (decode says so and gives nothing).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ladarsim/dataset/ouster_pcap.h"
#include "shared_data.h"
#include "skip.h"

namespace ladarsim::test {

struct Unit {
    const char* stem;
    double spec_range_m;          // Ouster's datasheet, 80 % target
    std::size_t returns;          // counted by an independent Python reading of the capture
    double lowest_ground_share;   // of the lowest channel's points near one plane (measured 62 %, 46 %)
};
inline constexpr Unit kOs1{"OS-1-32-G_v2.1.1_1024x10", 120.0, 27310, 0.55};
inline constexpr Unit kOs2{"OS-2-128-U1_v2.3.0_1024x10", 240.0, 119682, 0.40};

inline std::filesystem::path data_file(const Unit& u, const char* extension) {
    return shared_data("ouster") / (std::string(u.stem) + extension);
}

struct Capture {
    OusterCalibration calibration;
    std::vector<Frame> frames;
};

inline std::optional<Capture> decode(const Unit& u) {
    if (!std::filesystem::exists(data_file(u, ".pcap")) || !std::filesystem::exists(data_file(u, ".json"))) {
        skip("shared data not present: " + data_file(u, ".pcap").string());
        return std::nullopt;
    }
    Capture c{read_ouster_metadata(data_file(u, ".json")), {}};
    c.frames = read_ouster_pcap(data_file(u, ".pcap"), c.calibration);
    return c;
}

}  // namespace ladarsim::test
