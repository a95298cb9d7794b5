#include "ladarsim/scene/las_file.h"

#include <cstring>
#include <fstream>
#include <string>

#include "ladarsim/core/input_error.h"

namespace ladarsim::scene {
namespace {

template <typename T>
T at(const std::vector<char>& bytes, std::size_t offset) {
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof v);  // LAS is little-endian, as is every target we build for
    return v;
}

}  // namespace

LasCloud read_las(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name, "(file)", "cannot open");
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 227 || std::string(bytes.data(), 4) != "LASF") throw InputError(name, "signature", "not a LAS file");
    const int major = static_cast<unsigned char>(bytes[24]), minor = static_cast<unsigned char>(bytes[25]);
    if (major != 1 || minor < 2 || minor > 4)
        throw InputError(name, "version", "LAS " + std::to_string(major) + "." + std::to_string(minor) + " is not supported (1.2-1.4)");
    const auto data_offset = at<std::uint32_t>(bytes, 96);
    const int format = static_cast<unsigned char>(bytes[104]) & 0x3F;  // bits 6-7 flag LAZ compression
    if (static_cast<unsigned char>(bytes[104]) & 0xC0) throw InputError(name, "point_data_format", "compressed (LAZ) files are not supported");
    const auto record_length = at<std::uint16_t>(bytes, 105);
    std::uint64_t count = at<std::uint32_t>(bytes, 107);
    if (minor == 4 && bytes.size() >= 255 && count == 0) count = at<std::uint64_t>(bytes, 247);
    const bool legacy = format <= 3;
    if (!(legacy || (format >= 6 && format <= 8)))
        throw InputError(name, "point_data_format", std::to_string(format) + " is not supported (0-3, 6-8)");
    if (record_length < (legacy ? 20 : 30)) throw InputError(name, "point_data_record_length", "too short for its format");
    if (data_offset + count * record_length > bytes.size())
        throw InputError(name, "number_of_point_records", "the file ends before its " + std::to_string(count) + " points");
    const double scale[3] = {at<double>(bytes, 131), at<double>(bytes, 139), at<double>(bytes, 147)};
    const double offset[3] = {at<double>(bytes, 155), at<double>(bytes, 163), at<double>(bytes, 171)};
    LasCloud cloud;
    cloud.points.reserve(count);
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::size_t r = data_offset + i * record_length;
        cloud.points.emplace_back(at<std::int32_t>(bytes, r) * scale[0] + offset[0], at<std::int32_t>(bytes, r + 4) * scale[1] + offset[1],
                                  at<std::int32_t>(bytes, r + 8) * scale[2] + offset[2]);
        cloud.intensity.push_back(at<std::uint16_t>(bytes, r + 12));
        // Formats 0-5 keep a 5-bit class in byte 15; formats 6-10 a full byte at 16.
        cloud.classification.push_back(legacy ? static_cast<std::uint8_t>(bytes[r + 15] & 0x1F) : static_cast<std::uint8_t>(bytes[r + 16]));
    }
    return cloud;
}

}  // namespace ladarsim::scene
