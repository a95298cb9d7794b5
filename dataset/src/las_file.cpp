#include "ladarsim/dataset/las_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {

// LAS is little-endian; the records are written as the host's memory image.
static_assert(std::endian::native == std::endian::little, "LAS I/O assumes a little-endian host");

namespace {

constexpr int kHeaderBytes = 375;       // LAS 1.4
constexpr int kVlrHeaderBytes = 54;
constexpr int kDescriptorBytes = 192;   // one extra-bytes descriptor
constexpr int kMaxReturns = 15;         // 4 bits in format 6

// Byte offsets of the LAS 1.4 header fields the reader needs.
constexpr int kAtGlobalEncoding = 6;
constexpr int kAtVersion = 24;
constexpr int kAtSystemIdentifier = 26;
constexpr int kAtGeneratingSoftware = 58;
constexpr int kAtHeaderSize = 94;
constexpr int kAtPointOffset = 96;
constexpr int kAtVlrCount = 100;
constexpr int kAtFormat = 104;
constexpr int kAtRecordLength = 105;
constexpr int kAtScale = 131;
constexpr int kAtOffset = 155;
constexpr int kAtPointCount = 247;

int type_bytes(LasExtraField::Type) { return 4; }

/// Little-endian bytes appended to a buffer.
class Bytes {
public:
    template <typename T>
    void put(T value) {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof raw);
        data_.append(raw, sizeof raw);
    }
    /// `text` in a fixed field of `width` bytes, zero-padded (truncated when longer).
    void put_text(const std::string& text, std::size_t width) {
        const std::string cut = text.substr(0, std::min(text.size(), width));
        data_ += cut;
        data_.append(width - cut.size(), '\0');
    }
    void put_zeros(std::size_t n) { data_.append(n, '\0'); }
    std::string& data() { return data_; }

private:
    std::string data_;
};

template <typename T>
T get(const std::string& bytes, std::size_t at) {
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof value);
    return value;
}

std::string text_at(const std::string& bytes, std::size_t at, std::size_t width) {
    std::string text = bytes.substr(at, width);
    return text.substr(0, text.find('\0'));
}

/// The extra-bytes VLR's payload: one 192-byte descriptor per field.
std::string extra_bytes_descriptors(const std::vector<LasExtraField>& fields) {
    Bytes b;
    for (const LasExtraField& f : fields) {
        b.put_zeros(2);  // reserved
        b.put(static_cast<std::uint8_t>(f.type));
        b.put(static_cast<std::uint8_t>(f.has_no_data ? 1 : 0));  // options: bit 0, no_data is valid
        b.put_text(f.name, 32);
        b.put_zeros(4);  // unused
        // no_data, min, max, scale, offset: 8 bytes each (the type's own, widened), each followed
        // by 16 deprecated bytes; only no_data is used.
        if (f.type == LasExtraField::Type::float32)
            b.put(f.no_data);
        else
            b.put(static_cast<std::uint64_t>(f.no_data));
        b.put_zeros(16 + 4 * (8 + 16));
        b.put_text(f.description, 32);
    }
    return b.data();
}

std::vector<LasExtraField> read_descriptors(const std::string& payload, const std::string& file) {
    if (payload.size() % kDescriptorBytes != 0)
        throw InputError(file, "extra bytes VLR", "is " + std::to_string(payload.size()) + " bytes, not a multiple of 192");
    std::vector<LasExtraField> fields;
    for (std::size_t at = 0; at < payload.size(); at += kDescriptorBytes) {
        LasExtraField f;
        const auto type = get<std::uint8_t>(payload, at + 2);
        if (type != static_cast<std::uint8_t>(LasExtraField::Type::uint32) &&
            type != static_cast<std::uint8_t>(LasExtraField::Type::float32))
            throw InputError(file, "extra bytes VLR", "data type " + std::to_string(type) + " is not read (only 5, uint32, and 9, float32)");
        f.type = static_cast<LasExtraField::Type>(type);
        f.has_no_data = (get<std::uint8_t>(payload, at + 3) & 1u) != 0;
        f.name = text_at(payload, at + 4, 32);
        f.no_data = f.type == LasExtraField::Type::float32 ? get<double>(payload, at + 40)
                                                           : static_cast<double>(get<std::uint64_t>(payload, at + 40));
        f.description = text_at(payload, at + 160, 32);
        fields.push_back(std::move(f));
    }
    return fields;
}

std::int32_t scaled(double value, double scale, double offset, int axis, const std::filesystem::path& path) {
    const double units = std::round((value - offset) / scale);
    if (!(units >= std::numeric_limits<std::int32_t>::min() && units <= std::numeric_limits<std::int32_t>::max()))
        throw InputError(path.string(), std::string("points.") + "xyz"[axis],
                         std::to_string(value) + " m does not fit a LAS int32 at scale " + std::to_string(scale) +
                             " and offset " + std::to_string(offset));
    return static_cast<std::int32_t>(units);
}

}  // namespace

void write_las(const std::filesystem::path& path, const LasCloud& cloud) {
    int extra_bytes = 0;
    for (const LasExtraField& f : cloud.extra_fields) extra_bytes += type_bytes(f.type);
    const std::string descriptors = extra_bytes_descriptors(cloud.extra_fields);
    const int vlrs = cloud.extra_fields.empty() ? 0 : 1;
    const std::uint32_t point_offset = kHeaderBytes + (vlrs ? kVlrHeaderBytes + static_cast<std::uint32_t>(descriptors.size()) : 0);

    // Points first: the header needs their bounds and counts by return.
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
    std::array<std::uint64_t, kMaxReturns> by_return{};
    Bytes points;
    for (const LasPoint& p : cloud.points) {
        if (p.return_number < 1 || p.return_number > kMaxReturns || p.number_of_returns < 1 || p.number_of_returns > kMaxReturns)
            throw InputError(path.string(), "points.return_number",
                             "return " + std::to_string(p.return_number) + " of " + std::to_string(p.number_of_returns) +
                                 " is outside the format's 1..15");
        if (p.extra.size() != cloud.extra_fields.size())
            throw InputError(path.string(), "points.extra", "a point has " + std::to_string(p.extra.size()) +
                                                               " extra values for " + std::to_string(cloud.extra_fields.size()) + " fields");
        Eigen::Vector3d stored;
        for (int axis = 0; axis < 3; ++axis) {
            const std::int32_t units = scaled(p.position[axis], cloud.scale[axis], cloud.offset[axis], axis, path);
            points.put(units);
            stored[axis] = units * cloud.scale[axis] + cloud.offset[axis];
        }
        low = low.cwiseMin(stored);
        high = high.cwiseMax(stored);
        ++by_return[p.return_number - 1];
        points.put(p.intensity);
        points.put(static_cast<std::uint8_t>(p.return_number | (p.number_of_returns << 4)));
        points.put(std::uint8_t{0});  // classification flags, scanner channel, scan direction, edge of flight line
        points.put(p.classification);
        points.put(p.user_data);
        points.put(p.scan_angle);
        points.put(p.point_source_id);
        points.put(p.gps_time);
        for (std::size_t i = 0; i < p.extra.size(); ++i) {
            if (cloud.extra_fields[i].type == LasExtraField::Type::float32)
                points.put(static_cast<float>(p.extra[i]));
            else
                points.put(static_cast<std::uint32_t>(p.extra[i]));
        }
    }
    if (cloud.points.empty()) low = high = Eigen::Vector3d::Zero();

    Bytes h;
    h.put_text("LASF", 4);
    h.put(std::uint16_t{0});  // file source ID
    // Bit 4: coordinate system as WKT (format 6 requires it); bit 0: the GPS time's kind.
    h.put(static_cast<std::uint16_t>((1u << 4) | (cloud.adjusted_standard_gps_time ? 1u : 0u)));
    h.put_zeros(16);  // project GUID
    h.put(std::uint8_t{1});
    h.put(std::uint8_t{4});
    h.put_text(cloud.system_identifier, 32);
    h.put_text(cloud.generating_software, 32);
    h.put(std::uint16_t{0});  // creation day of year: unknown
    h.put(std::uint16_t{0});  // creation year: unknown
    h.put(static_cast<std::uint16_t>(kHeaderBytes));
    h.put(point_offset);
    h.put(static_cast<std::uint32_t>(vlrs));
    h.put(std::uint8_t{6});
    h.put(static_cast<std::uint16_t>(kLasFormat6Bytes + extra_bytes));
    h.put_zeros(4 + 5 * 4);  // legacy counts: 0 for format 6
    for (int axis = 0; axis < 3; ++axis) h.put(cloud.scale[axis]);
    for (int axis = 0; axis < 3; ++axis) h.put(cloud.offset[axis]);
    for (int axis = 0; axis < 3; ++axis) {
        h.put(high[axis]);
        h.put(low[axis]);
    }
    h.put(std::uint64_t{0});  // start of waveform data packets: none
    h.put(std::uint64_t{0});  // start of the first EVLR: none
    h.put(std::uint32_t{0});  // EVLRs
    h.put(static_cast<std::uint64_t>(cloud.points.size()));
    for (const std::uint64_t n : by_return) h.put(n);
    if (vlrs) {
        h.put(std::uint16_t{0});  // reserved
        h.put_text("LASF_Spec", 16);
        h.put(std::uint16_t{4});  // extra bytes
        h.put(static_cast<std::uint16_t>(descriptors.size()));
        h.put_text("ladarsim per-point fields", 32);
        h.data() += descriptors;
    }

    AtomicFile file(path);
    file.stream().write(h.data().data(), static_cast<std::streamsize>(h.data().size()));
    file.stream().write(points.data().data(), static_cast<std::streamsize>(points.data().size()));
    file.commit();
}

LasCloud read_las(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file, "(file)", "cannot be opened");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < kHeaderBytes || bytes.compare(0, 4, "LASF") != 0)
        throw InputError(file, "header", "is not a LAS file (no LASF signature and 375-byte header)");
    if (get<std::uint8_t>(bytes, kAtVersion) != 1 || get<std::uint8_t>(bytes, kAtVersion + 1) != 4)
        throw InputError(file, "header.version", "is not LAS 1.4");
    if (get<std::uint8_t>(bytes, kAtFormat) != 6)
        throw InputError(file, "header.point_data_format", "is " + std::to_string(get<std::uint8_t>(bytes, kAtFormat)) + ", not 6");

    LasCloud cloud;
    cloud.adjusted_standard_gps_time = (get<std::uint16_t>(bytes, kAtGlobalEncoding) & 1u) != 0;
    cloud.system_identifier = text_at(bytes, kAtSystemIdentifier, 32);
    cloud.generating_software = text_at(bytes, kAtGeneratingSoftware, 32);
    for (int axis = 0; axis < 3; ++axis) {
        cloud.scale[axis] = get<double>(bytes, kAtScale + 8 * axis);
        cloud.offset[axis] = get<double>(bytes, kAtOffset + 8 * axis);
    }
    std::size_t at = get<std::uint16_t>(bytes, kAtHeaderSize);
    const std::uint32_t vlrs = get<std::uint32_t>(bytes, kAtVlrCount);
    for (std::uint32_t v = 0; v < vlrs; ++v) {
        if (at + kVlrHeaderBytes > bytes.size()) throw InputError(file, "VLR " + std::to_string(v), "truncated");
        const std::string user = text_at(bytes, at + 2, 16);
        const auto record = get<std::uint16_t>(bytes, at + 18);
        const auto length = get<std::uint16_t>(bytes, at + 20);
        at += kVlrHeaderBytes;
        if (at + length > bytes.size()) throw InputError(file, "VLR " + std::to_string(v), "truncated");
        if (user == "LASF_Spec" && record == 4) cloud.extra_fields = read_descriptors(bytes.substr(at, length), file);
        at += length;
    }

    const std::size_t record_length = get<std::uint16_t>(bytes, kAtRecordLength);
    std::size_t extra_bytes = 0;
    for (const LasExtraField& f : cloud.extra_fields) extra_bytes += static_cast<std::size_t>(type_bytes(f.type));
    if (record_length != kLasFormat6Bytes + extra_bytes)
        throw InputError(file, "header.point_data_record_length",
                         "is " + std::to_string(record_length) + ", not 30 plus the " + std::to_string(extra_bytes) +
                             " extra bytes the VLR describes");
    const std::uint64_t count = get<std::uint64_t>(bytes, kAtPointCount);
    at = get<std::uint32_t>(bytes, kAtPointOffset);
    if (at > bytes.size() || (bytes.size() - at) / record_length < count)
        throw InputError(file, "points", "truncated: the header says " + std::to_string(count) + " points");
    cloud.points.resize(count);
    for (LasPoint& p : cloud.points) {
        for (int axis = 0; axis < 3; ++axis) p.position[axis] = get<std::int32_t>(bytes, at + 4 * axis) * cloud.scale[axis] + cloud.offset[axis];
        p.intensity = get<std::uint16_t>(bytes, at + 12);
        const auto returns = get<std::uint8_t>(bytes, at + 14);
        p.return_number = returns & 0x0Fu;
        p.number_of_returns = returns >> 4;
        p.classification = get<std::uint8_t>(bytes, at + 16);
        p.user_data = get<std::uint8_t>(bytes, at + 17);
        p.scan_angle = get<std::int16_t>(bytes, at + 18);
        p.point_source_id = get<std::uint16_t>(bytes, at + 20);
        p.gps_time = get<double>(bytes, at + 22);
        std::size_t field_at = at + kLasFormat6Bytes;
        for (const LasExtraField& f : cloud.extra_fields) {
            // Each widened to double on its own: a conditional of float and uint32 would round ids to float.
            if (f.type == LasExtraField::Type::float32)
                p.extra.push_back(static_cast<double>(get<float>(bytes, field_at)));
            else
                p.extra.push_back(static_cast<double>(get<std::uint32_t>(bytes, field_at)));
            field_at += static_cast<std::size_t>(type_bytes(f.type));
        }
        at += record_length;
    }
    return cloud;
}

}  // namespace ladarsim
