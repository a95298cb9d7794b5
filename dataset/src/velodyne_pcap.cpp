#include "ladarsim/dataset/velodyne_pcap.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <tuple>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/pcap_udp.h"

namespace ladarsim {
namespace {

constexpr std::size_t kPayload = 1206;
constexpr double kElevationDeg[16] = {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
constexpr double kFiringSequenceS = 55.296e-6;  // two per block
constexpr double kFiringS = 2.304e-6;           // between channels

/// Row of a channel: 0 for the highest (+15 deg), 15 for the lowest.
int row_of(int channel) {
    return static_cast<int>(std::count_if(std::begin(kElevationDeg), std::end(kElevationDeg),
                                          [&](double e) { return e > kElevationDeg[channel]; }));
}

}  // namespace

std::vector<Frame> read_velodyne_vlp16_pcap(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::vector<Frame> frames(1);
    double last_azimuth = -1.0;
    int sequence = 0;
    for_each_udp_datagram(file, [&](const UdpDatagram& d) {
        if (d.payload.size() != kPayload) return;  // position (GPS) packets and others
        const auto& b = d.payload;
        const double packet_time = d.time_s;
        for (int block = 0; block < 12; ++block) {
            const std::size_t base = 100 * static_cast<std::size_t>(block);
            if (read_le<std::uint16_t>(b, base) != 0xEEFF) throw InputError(name, "block flag", "not a Velodyne data block");
            const double azimuth = read_le<std::uint16_t>(b, base + 2) / 100.0;
            // The second firing sequence lies half way to the next block's azimuth.
            const std::size_t next = block < 11 ? base + 100 : base - 100;
            double step = (read_le<std::uint16_t>(b, next + 2) / 100.0 - azimuth) * (block < 11 ? 1.0 : -1.0);
            if (step < -180.0) step += 360.0;
            if (step > 180.0) step -= 360.0;
            for (int half = 0; half < 2; ++half) {
                const double az_deg = std::fmod(azimuth + 0.5 * half * step + 360.0, 360.0);
                if (last_azimuth >= 0.0 && az_deg < last_azimuth - 180.0) {
                    frames.emplace_back();
                    sequence = 0;
                }
                last_azimuth = az_deg;
                for (int channel = 0; channel < 16; ++channel) {
                    const std::size_t p = base + 4 + 3 * static_cast<std::size_t>(16 * half + channel);
                    const double range = read_le<std::uint16_t>(b, p) * 0.002;
                    if (range <= 0.0) continue;
                    const double el = kElevationDeg[channel] * std::numbers::pi / 180.0;
                    // Velodyne azimuth turns clockwise from forward; ours is positive to the left.
                    const double az = std::remainder(-az_deg, 360.0) * std::numbers::pi / 180.0;
                    Return r;
                    r.range_m = range;
                    r.position_sensor = Eigen::Vector3d(range * std::cos(el) * std::cos(az), range * std::cos(el) * std::sin(az),
                                                        range * std::sin(el))
                                            .cast<float>();
                    r.intensity = static_cast<unsigned char>(b[p + 2]);
                    r.time_s = packet_time + (2 * block + half) * kFiringSequenceS + channel * kFiringS;
                    r.beam_az_rad = static_cast<float>(az);
                    r.beam_el_rad = static_cast<float>(el);
                    r.column = static_cast<std::uint16_t>(sequence);
                    r.row = static_cast<std::uint16_t>(row_of(channel));
                    frames.back().returns.push_back(r);
                }
                ++sequence;
            }
        }
    });
    std::erase_if(frames, [](const Frame& f) { return f.returns.empty(); });
    if (frames.empty()) throw InputError(name, "packets", "no VLP-16 data packets");
    for (std::size_t i = 0; i < frames.size(); ++i) {
        Frame& f = frames[i];
        f.index = i;
        f.rows = 16;
        f.columns = 0;
        for (const Return& r : f.returns) f.columns = std::max(f.columns, r.column + 1);
        f.start_time_s = f.returns.front().time_s;
        f.end_time_s = f.returns.back().time_s;
        std::stable_sort(f.returns.begin(), f.returns.end(),
                         [](const Return& a, const Return& b) { return std::tie(a.row, a.column) < std::tie(b.row, b.column); });
    }
    return frames;
}

}  // namespace ladarsim
