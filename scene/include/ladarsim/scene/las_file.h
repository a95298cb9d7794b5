#pragma once
// Uncompressed LAS 1.2-1.4 point clouds (ASPRS), the format recorded maps usually come in; Debian
// ships no LAS library, and the format is a fixed header plus fixed-size records.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace ladarsim::scene {

/// Points of a LAS file in the file's own units (scale and offset of its header applied).
struct LasCloud {
    std::vector<Eigen::Vector3d> points;
    std::vector<std::uint16_t> intensity;
    std::vector<std::uint8_t> classification;
};

/// Reads point data formats 0-3 and 6-8. Throws InputError naming the file and the header field
/// for anything else (compressed LAZ, other formats, truncated files).
LasCloud read_las(const std::filesystem::path& file);

}  // namespace ladarsim::scene
