#pragma once
// LAS 1.4 point clouds (ASPRS LAS Specification 1.4 R15), as surveying and GIS tools read them:
// point data record format 6 (30 bytes: X Y Z as scaled int32, intensity, return number and
// number of returns in 4 bits each, classification, user data, scan angle, point source ID, GPS
// time) followed by extra bytes the file describes in its "LASF_Spec" VLR of record ID 4. Only
// what ladarsim writes is read back: format 6, little-endian, uint32 and float32 extra bytes.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ladarsim {

/// One extra-bytes field of every point (a descriptor of the extra-bytes VLR).
struct LasExtraField {
    enum class Type : std::uint8_t { uint32 = 5, float32 = 9 };  ///< the specification's data_type codes
    std::string name;         ///< up to 32 characters
    Type type = Type::uint32;
    std::string description;  ///< up to 32 characters
    /// The value that stands for "none" (the descriptor's no_data, option bit 0), if any.
    bool has_no_data = false;
    double no_data = 0.0;
};

struct LasPoint {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< metres, before scaling
    std::uint16_t intensity = 0;
    std::uint8_t return_number = 1;       ///< 1..15
    std::uint8_t number_of_returns = 1;   ///< 1..15
    std::uint8_t classification = 0;      ///< ASPRS code
    std::uint8_t user_data = 0;
    std::int16_t scan_angle = 0;          ///< units of 0.006 deg, -30000..30000
    std::uint16_t point_source_id = 0;
    double gps_time = 0.0;
    std::vector<double> extra;            ///< one value per LasCloud::extra_fields, in their order
};

struct LasCloud {
    std::string system_identifier;   ///< up to 32 characters
    std::string generating_software; ///< up to 32 characters
    Eigen::Vector3d scale = Eigen::Vector3d::Constant(1e-4);
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    /// Global encoding bit 0: GPS time is adjusted standard GPS time (else GPS week time).
    bool adjusted_standard_gps_time = false;
    std::vector<LasExtraField> extra_fields;
    std::vector<LasPoint> points;
};

/// Bytes of a format 6 point record before its extra bytes.
inline constexpr int kLasFormat6Bytes = 30;

/// Writes `cloud` as a LAS 1.4 file of point format 6 (atomically: see AtomicFile). The header
/// carries the bounds and the counts by return of the points; the creation date is left 0
/// (unknown), so that the same cloud always gives the same bytes; global encoding bit 4 (WKT) is
/// set, as format 6 requires, with no coordinate system VLR: the frames are local. Throws
/// InputError naming the file for a position that does not fit the int32 range at the cloud's
/// scale and offset, or a return number or count outside 1..15.
void write_las(const std::filesystem::path& path, const LasCloud& cloud);

/// Reads a file write_las wrote (or another LAS 1.4 file of point format 6 whose extra bytes are
/// described, each a uint32 or a float32). Throws InputError naming the file and the part (header field, VLR,
/// points) that is missing, truncated or not of that kind.
LasCloud read_las(const std::filesystem::path& path);

}  // namespace ladarsim
