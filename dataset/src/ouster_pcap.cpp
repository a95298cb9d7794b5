#include "ladarsim/dataset/ouster_pcap.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <span>
#include <string_view>
#include <tuple>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/pcap_udp.h"
#include "ladarsim/core/units.h"

namespace ladarsim {
namespace {


/// `count` numbers in [lo, hi], as every per-channel table and matrix of the metadata is.
std::vector<double> numbers(JsonFields& fields, const std::string& key, std::size_t count, double lo, double hi) {
    const nlohmann::json& array = fields.array(key);
    if (array.size() != count) {
        fields.fail(key, "expected " + std::to_string(count) + " numbers, found " + std::to_string(array.size()));
    }
    std::vector<double> out;
    for (const nlohmann::json& v : array) {
        if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi)) {
            fields.fail(key, "element " + std::to_string(out.size()) + " is " + v.dump() + ", not a number in [" +
                                 nlohmann::json(lo).dump() + ", " + nlohmann::json(hi).dump() + "]");
        }
        out.push_back(v.get<double>());
    }
    return out;
}

std::vector<int> whole_numbers(JsonFields& fields, const std::string& key, std::size_t count, int lo, int hi) {
    std::vector<int> out;
    for (double x : numbers(fields, key, count, lo, hi)) {
        if (x != std::floor(x)) fields.fail(key, "element " + std::to_string(out.size()) + " is not a whole number");
        out.push_back(static_cast<int>(x));
    }
    return out;
}

/// "1024x10": columns per revolution and revolutions per second.
std::pair<int, int> lidar_mode(JsonFields& fields) {
    const std::string mode = fields.string("lidar_mode");
    int columns = 0, rate = 0;
    const char* end = mode.data() + mode.size();
    const auto [x, e1] = std::from_chars(mode.data(), end, columns);
    const auto [last, e2] = x < end && *x == 'x' ? std::from_chars(x + 1, end, rate) : std::from_chars_result{x, std::errc::invalid_argument};
    if (e1 != std::errc() || e2 != std::errc() || last != end || columns <= 0 || rate <= 0) {
        fields.fail("lidar_mode", "\"" + mode + "\" is not columns x rate, like \"1024x10\"");
    }
    return {columns, rate};
}

/// Where a packet profile keeps its fields (Ouster's "lidar data packet format"). LEGACY has no
/// packet header: every column carries its own frame id and ends in a 32-bit status; the newer
/// profiles put frame id and serial number in a packet header and the status in the column's.
struct PacketLayout {
    bool legacy = true;
    std::size_t packet_header = 0, column_header = 16, column_footer = 4, packet_footer = 0;
    std::uint32_t range_mask = 0x000FFFFFu;  // millimetres
    static constexpr std::size_t kPixel = 12;

    std::size_t column_size(const OusterCalibration& c) const {
        return column_header + kPixel * static_cast<std::size_t>(c.pixels_per_column) + column_footer;
    }
    std::size_t packet_size(const OusterCalibration& c) const {
        return packet_header + static_cast<std::size_t>(c.columns_per_packet) * column_size(c) + packet_footer;
    }
};

PacketLayout packet_layout(const OusterCalibration& c) {
    if (c.udp_profile_lidar == "LEGACY") return PacketLayout{};
    if (c.udp_profile_lidar == "RNG19_RFL8_SIG16_NIR16") return PacketLayout{false, 32, 12, 0, 32, 0x0007FFFFu};
    throw InputError(c.metadata_file.string(), "udp_profile_lidar",
                     "\"" + c.udp_profile_lidar + "\" packets are not decoded (LEGACY and RNG19_RFL8_SIG16_NIR16 are)");
}

/// Ouster's range-to-xyz formula for one unit, in ladarsim's frame.
class BeamGeometry {
public:
    explicit BeamGeometry(const OusterCalibration& c)
        : columns_(c.columns_per_frame), origin_offset_m_(c.lidar_origin_to_beam_origin_mm * 1e-3),
          rotation_(c.lidar_to_sensor.topLeftCorner<3, 3>()) {
        // Ouster's azimuths turn clockwise; angles about +z turn counter-clockwise.
        for (double a : c.beam_azimuth_deg) azimuth_rad_.push_back(-a * kDeg);
        for (double a : c.beam_altitude_deg) altitude_rad_.push_back(a * kDeg);
    }

    /// The return of channel `row` in column `column` (measurement_id) at range `range_m`.
    Return at(int column, int row, double range_m) const {
        // The head turns clockwise: measurement_id 0 points along the lidar frame's +x.
        const double encoder = 2.0 * std::numbers::pi * (1.0 - static_cast<double>(column) / columns_);
        const double az = encoder + azimuth_rad_[static_cast<std::size_t>(row)];
        const double el = altitude_rad_[static_cast<std::size_t>(row)];
        const Eigen::Vector3d direction = rotation_ * Eigen::Vector3d(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
        // The beam leaves the head off its axis, towards the encoder angle; the range counts from the axis.
        const Eigen::Vector3d origin = rotation_ * Eigen::Vector3d(std::cos(encoder), std::sin(encoder), 0.0) * origin_offset_m_;
        Return r;
        r.range_m = range_m;
        r.position_sensor = (origin + (range_m - origin_offset_m_) * direction).cast<float>();
        r.beam_az_rad = static_cast<float>(std::atan2(direction.y(), direction.x()));
        r.beam_el_rad = static_cast<float>(std::asin(std::clamp(direction.z(), -1.0, 1.0)));
        r.column = static_cast<std::uint16_t>(column);
        r.row = static_cast<std::uint16_t>(row);
        return r;
    }

private:
    int columns_;
    double origin_offset_m_;
    Eigen::Matrix3d rotation_;
    std::vector<double> azimuth_rad_, altitude_rad_;
};

}  // namespace

OusterCalibration read_ouster_metadata(const std::filesystem::path& file) {
    const std::string name = file.string();
    const nlohmann::json doc = read_json(file);
    JsonFields top(doc, name, "");
    // Firmware 2.4 moved the flat keys into sections; each field is read where its layout keeps it.
    const bool sectioned = top.has("beam_intrinsics");
    auto section = [&](const std::string& key) { return sectioned ? JsonFields(top.object(key), name, key) : top; };
    JsonFields info = section("sensor_info"), beams = section("beam_intrinsics"), lidar = section("lidar_intrinsics"),
               config = section("config_params");
    const std::string format_key = sectioned ? "lidar_data_format" : "data_format";
    JsonFields format(top.object(format_key), name, format_key);

    OusterCalibration c;
    c.metadata_file = file;
    c.product_line = info.string("prod_line");
    c.serial = info.string("prod_sn");
    c.firmware = info.string("build_rev");
    c.columns_per_frame = static_cast<int>(format.integer("columns_per_frame", 1, 65535));
    c.pixels_per_column = static_cast<int>(format.integer("pixels_per_column", 1, 65535));
    c.columns_per_packet = static_cast<int>(format.integer("columns_per_packet", 1, 65535));
    const auto [mode_columns, rate] = lidar_mode(config);
    if (mode_columns != c.columns_per_frame) {
        config.fail("lidar_mode", "says " + std::to_string(mode_columns) + " columns, " + format.path_of("columns_per_frame") +
                                      " says " + std::to_string(c.columns_per_frame));
    }
    c.frame_rate_hz = rate;
    const auto channels = static_cast<std::size_t>(c.pixels_per_column);
    c.beam_altitude_deg = numbers(beams, "beam_altitude_angles", channels, -90.0, 90.0);
    c.beam_azimuth_deg = numbers(beams, "beam_azimuth_angles", channels, -180.0, 180.0);
    c.lidar_origin_to_beam_origin_mm = beams.number("lidar_origin_to_beam_origin_mm", 0.0, 1000.0);
    const std::vector<double> t = numbers(lidar, "lidar_to_sensor_transform", 16, -1e6, 1e6);
    c.lidar_to_sensor = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(t.data());
    const Eigen::Matrix3d rotation = c.lidar_to_sensor.topLeftCorner<3, 3>();
    if (!(rotation * rotation.transpose()).isIdentity(1e-3) || rotation.determinant() < 0.0 ||
        !c.lidar_to_sensor.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1))) {
        lidar.fail("lidar_to_sensor_transform", "not a rotation and translation (row-major 4 x 4)");
    }
    c.pixel_shift_by_row = whole_numbers(format, "pixel_shift_by_row", channels, -c.columns_per_frame, c.columns_per_frame);
    const std::vector<int> window = whole_numbers(format, "column_window", 2, 0, c.columns_per_frame - 1);
    c.column_window = {window[0], window[1]};
    c.udp_profile_lidar = format.string("udp_profile_lidar", c.udp_profile_lidar);
    c.udp_port_lidar = static_cast<int>(config.integer("udp_port_lidar", 1, 65535, c.udp_port_lidar));
    return c;
}

std::vector<Frame> read_ouster_pcap(const std::filesystem::path& pcap, const OusterCalibration& c) {
    const std::string name = pcap.string();
    const PacketLayout layout = packet_layout(c);
    const std::size_t column_size = layout.column_size(c), packet_size = layout.packet_size(c);
    const BeamGeometry geometry(c);
    std::vector<Frame> frames;
    int frame_id = -1;
    for_each_udp_datagram(pcap, [&](const UdpDatagram& d) {
        if (d.destination_port != c.udp_port_lidar) return;  // IMU packets and others
        const std::string where = "record " + std::to_string(d.record);
        if (d.payload.size() != packet_size) {
            throw InputError(name, where, "a lidar packet of " + std::to_string(d.payload.size()) + " bytes; " + c.udp_profile_lidar +
                                              " packets of " + std::to_string(c.columns_per_packet) + " columns x " +
                                              std::to_string(c.pixels_per_column) + " channels have " + std::to_string(packet_size));
        }
        if (!layout.legacy) {
            const std::uint64_t serial = read_le<std::uint64_t>(d.payload, 7) & 0xFF'FFFF'FFFFull;  // 40 bits
            if (read_le<std::uint16_t>(d.payload, 0) != 1) throw InputError(name, where, "packet type is not lidar data");
            if (std::to_string(serial) != c.serial) {
                throw InputError(name, where, "packet of unit " + std::to_string(serial) + ", calibration of unit " + c.serial);
            }
        }
        for (std::size_t k = 0; k < static_cast<std::size_t>(c.columns_per_packet); ++k) {
            const auto column = d.payload.subspan(layout.packet_header + k * column_size, column_size);
            // Bit 0 says the column was measured: LEGACY sets all 32 status bits, the others that one.
            const std::uint32_t status = layout.legacy ? read_le<std::uint32_t>(column, column_size - 4) : read_le<std::uint16_t>(column, 10);
            if (!(status & 1u)) continue;
            const int measurement_id = read_le<std::uint16_t>(column, 8);
            if (measurement_id >= c.columns_per_frame) {
                throw InputError(name, where, "measurement_id " + std::to_string(measurement_id) + " beyond the frame's " +
                                                  std::to_string(c.columns_per_frame) + " columns");
            }
            const int id = layout.legacy ? read_le<std::uint16_t>(column, 10) : read_le<std::uint16_t>(d.payload, 2);
            const double time_s = static_cast<double>(read_le<std::uint64_t>(column, 0)) * 1e-9;
            if (frames.empty() || id != frame_id) {
                frames.emplace_back();
                frames.back().start_time_s = frames.back().end_time_s = time_s;
                frame_id = id;
            }
            Frame& f = frames.back();
            f.start_time_s = std::min(f.start_time_s, time_s);
            f.end_time_s = std::max(f.end_time_s, time_s);
            for (int row = 0; row < c.pixels_per_column; ++row) {
                const auto pixel = column.subspan(layout.column_header + PacketLayout::kPixel * static_cast<std::size_t>(row), PacketLayout::kPixel);
                const std::uint32_t range_mm = read_le<std::uint32_t>(pixel, 0) & layout.range_mask;
                if (range_mm == 0) continue;  // no return
                Return r = geometry.at(measurement_id, row, range_mm * 1e-3);
                r.intensity = layout.legacy ? read_le<std::uint16_t>(pixel, 4) : pixel[4];
                r.time_s = time_s;
                f.returns.push_back(r);
            }
        }
    });
    if (frames.empty()) {
        throw InputError(name, "packets", "no measured columns in Ouster lidar packets to UDP port " + std::to_string(c.udp_port_lidar));
    }
    for (std::size_t i = 0; i < frames.size(); ++i) {
        Frame& f = frames[i];
        f.index = i;
        f.rows = c.pixels_per_column;
        f.columns = c.columns_per_frame;
        std::stable_sort(f.returns.begin(), f.returns.end(),
                         [](const Return& a, const Return& b) { return std::tie(a.row, a.column) < std::tie(b.row, b.column); });
    }
    return frames;
}

}  // namespace ladarsim
