// A real VLP-16 capture decoded into frames: counts and ranges from its README, the geometry of
// its ground rings, and clear errors for anything else.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/velodyne_pcap.h"
#include "../support/scratch_dir.h"
#include "../support/shared_data.h"
#include "../support/skip.h"

using namespace ladarsim;

TEST_CASE("the recorded VLP-16 revolution decodes to its 19,579 returns at 2.4-110 m", "[velodyne]") {
    const std::filesystem::path file = test::shared_data("vlp16/velodyne_vlp16.pcap");
    if (!std::filesystem::exists(file)) LADARSIM_SKIP("shared data not present: " << file);
    const auto frames = read_velodyne_vlp16_pcap(file);
    std::size_t returns = 0;
    double lo = 1e9, hi = 0.0;
    std::vector<std::vector<double>> ground_z(16);
    for (const auto& f : frames) {
        returns += f.returns.size();
        for (const auto& r : f.returns) {
            lo = std::min(lo, r.range_m);
            hi = std::max(hi, r.range_m);
            REQUIRE(r.row < 16);
            // Beam angles and position agree: the point lies on its beam.
            REQUIRE(std::abs(r.beam_az_rad) <= M_PI + 1e-6);
            REQUIRE(std::abs(std::remainder(std::atan2(r.position_sensor.y(), r.position_sensor.x()) - r.beam_az_rad, 2.0 * M_PI)) < 1e-4);
            if (r.range_m < 25.0) ground_z[r.row].push_back(r.position_sensor.z());
        }
    }
    CHECK(returns == 19579);  // README
    CHECK(lo == Approx(2.43).margin(0.01));
    CHECK(hi == Approx(109.85).margin(0.01));
    // The lowest channels (-15 and -13 deg) see the same flat ground near the sensor: with the
    // VLP-16's channel order their median heights agree within 0.2 m. (Decoded with the HDL-32E
    // order the factory byte names, the same channel slots give ground heights 0.5 m apart.)
    auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    const double z15 = median(ground_z[15]), z13 = median(ground_z[13]);
    CHECK(std::abs(z15 - z13) < 0.2);
}

TEST_CASE("a file that is not a capture of VLP-16 packets is one InputError", "[velodyne]") {
    const test::ScratchDir dir;
    std::ofstream(dir / "x.pcap") << "not a capture at all, just text";
    CHECK_THROWS_AS(read_velodyne_vlp16_pcap(dir / "x.pcap"), InputError);
    CHECK_THROWS_AS(read_velodyne_vlp16_pcap(dir / "none.pcap"), InputError);
}
