#pragma once
// The PCD v0.7 point cloud format (PCL's, read by CloudCompare and pcl_viewer): the one reader
// and the one writer of ladarsim. What a cloud's fields mean is left to its users (frame_pcd.h
// for frames, scene/background_map.h for recorded maps).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ladarsim {

/// A field as a PCD header declares it: TYPE F (float), U (unsigned) or I (signed), SIZE in
/// bytes (4 or 8 for F; 1, 2, 4 or 8 for U and I), COUNT elements a point.
struct PcdField {
    std::string name;
    char type = 'F';
    int size = 4;
    int count = 1;
};

/// Whether a field of this TYPE and SIZE holds `value`: F any number (F4 rounding it), U and I
/// the whole numbers within their range.
bool pcd_type_holds(char type, int size, double value);

/// A cloud's points with their fields by name, whatever DATA encoding the file used.
class PcdCloud {
public:
    /// width x height points, every value 0.
    PcdCloud(std::vector<PcdField> fields, std::uint64_t width, std::uint64_t height);

    const std::vector<PcdField>& fields() const { return fields_; }
    std::uint64_t width() const { return width_; }
    std::uint64_t height() const { return height_; }
    /// width x height: an organised cloud keeps the beams without a return, as NaN points.
    std::uint64_t points() const { return width_ * height_; }

    /// The index of the field named `name`, if the cloud has one.
    std::optional<std::size_t> field(std::string_view name) const;
    /// Element `element` of field `field` of point `point`, as a double: exact for every TYPE
    /// and SIZE but 64-bit integers beyond 2^53.
    double value(std::uint64_t point, std::size_t field, int element = 0) const;
    /// Stores `value` converted to the field's TYPE and SIZE (which must hold it).
    void set(std::uint64_t point, std::size_t field, int element, double value);

    /// The points as PCD binary data: point after point, each field's SIZE x COUNT bytes in
    /// field order, little-endian.
    std::size_t point_step() const { return point_step_; }
    std::vector<char>& data() { return data_; }
    const std::vector<char>& data() const { return data_; }

private:
    char* at(std::uint64_t point, std::size_t field, int element);
    const char* at(std::uint64_t point, std::size_t field, int element) const;

    std::vector<PcdField> fields_;
    std::uint64_t width_;
    std::uint64_t height_;
    std::vector<std::size_t> offsets_;
    std::size_t point_step_ = 0;
    std::vector<char> data_;
};

/// Reads a PCD file: DATA ascii, binary or binary_compressed (LZF over the fields stored one
/// after another); FIELDS, or COLUMNS as before v0.7; SIZE, TYPE and COUNT (1 when absent) as
/// above; WIDTH and HEIGHT (1 when absent), or POINTS alone (unorganised, as PCL reads old files).
/// Every cloud ladarsim reads holds positions, so fields x, y and z are required. Throws
/// InputError naming the file and the header keyword (or DATA) for a malformed header,
/// truncated or corrupt data, or an ascii value that is not a number of its field's TYPE and SIZE.
PcdCloud read_pcd(const std::filesystem::path& path);

/// Writes `cloud` as a binary PCD, VIEWPOINT at the origin. Atomic (see AtomicFile).
void write_pcd(const std::filesystem::path& path, const PcdCloud& cloud);

}  // namespace ladarsim
