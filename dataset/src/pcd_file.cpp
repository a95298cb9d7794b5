#include "ladarsim/dataset/pcd_file.h"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "ladarsim/dataset/atomic_file.h"
#include "ladarsim/dataset/input_error.h"

namespace ladarsim {

// PCD binary data is the writer's memory image, and every PCD reader assumes little-endian.
static_assert(std::endian::native == std::endian::little, "PCD binary I/O assumes a little-endian host");

namespace {

/// One Return member as a PCD field. Values pass through double, which holds every F4, F8, U1,
/// U2 and U4 value exactly, so one table drives both the writer and the reader.
struct ReturnField {
    std::string_view name;
    char type;  ///< PCD TYPE: F float, U unsigned, I signed
    int size;   ///< bytes
    double (*get)(const Return&);
    void (*set)(Return&, double);
};

template <auto Member>
double get_member(const Return& r) {
    return static_cast<double>(r.*Member);
}

template <auto Member>
void set_member(Return& r, double value) {
    using T = std::remove_reference_t<decltype(r.*Member)>;
    r.*Member = static_cast<T>(value);
}

template <int Axis>
double get_position(const Return& r) {
    return static_cast<double>(r.position_sensor[Axis]);
}

template <int Axis>
void set_position(Return& r, double value) {
    r.position_sensor[Axis] = static_cast<float>(value);
}

double get_source(const Return& r) { return static_cast<double>(static_cast<std::uint8_t>(r.source)); }
void set_source(Return& r, double value) { r.source = static_cast<ReturnSource>(static_cast<std::uint8_t>(value)); }

constexpr std::array<ReturnField, 15> kReturnFields{{
    {"x", 'F', 4, get_position<0>, set_position<0>},
    {"y", 'F', 4, get_position<1>, set_position<1>},
    {"z", 'F', 4, get_position<2>, set_position<2>},
    {"intensity", 'F', 4, get_member<&Return::intensity>, set_member<&Return::intensity>},
    {"range_m", 'F', 8, get_member<&Return::range_m>, set_member<&Return::range_m>},
    {"time_s", 'F', 8, get_member<&Return::time_s>, set_member<&Return::time_s>},
    {"beam_az", 'F', 4, get_member<&Return::beam_az_rad>, set_member<&Return::beam_az_rad>},
    {"beam_el", 'F', 4, get_member<&Return::beam_el_rad>, set_member<&Return::beam_el_rad>},
    {"column", 'U', 2, get_member<&Return::column>, set_member<&Return::column>},
    {"row", 'U', 2, get_member<&Return::row>, set_member<&Return::row>},
    {"return_index", 'U', 1, get_member<&Return::return_index>, set_member<&Return::return_index>},
    {"object_id", 'U', 4, get_member<&Return::object_id>, set_member<&Return::object_id>},
    {"snr", 'F', 4, get_member<&Return::snr>, set_member<&Return::snr>},
    {"source", 'U', 1, get_source, set_source},
    {"pulse_offset", 'U', 1, get_member<&Return::pulse_offset>, set_member<&Return::pulse_offset>},
}};

constexpr std::size_t point_step_bytes() {
    std::size_t step = 0;
    for (const auto& f : kReturnFields) step += static_cast<std::size_t>(f.size);
    return step;
}

template <typename T>
void store(char* out, double value) {
    const T v = static_cast<T>(value);
    std::memcpy(out, &v, sizeof v);
}

void encode(char type, int size, double value, char* out) {
    if (type == 'F') {
        size == 4 ? store<float>(out, value) : store<double>(out, value);
    } else {
        switch (size) {
            case 1: store<std::uint8_t>(out, value); break;
            case 2: store<std::uint16_t>(out, value); break;
            default: store<std::uint32_t>(out, value); break;
        }
    }
}

template <typename T>
double load(const char* in) {
    T v;
    std::memcpy(&v, in, sizeof v);
    return static_cast<double>(v);
}

/// Only (type, size) pairs that parse_header accepted reach here.
double decode(char type, int size, const char* in) {
    if (type == 'F') return size == 4 ? load<float>(in) : load<double>(in);
    if (type == 'U') {
        switch (size) {
            case 1: return load<std::uint8_t>(in);
            case 2: return load<std::uint16_t>(in);
            case 4: return load<std::uint32_t>(in);
            default: return load<std::uint64_t>(in);
        }
    }
    switch (size) {
        case 1: return load<std::int8_t>(in);
        case 2: return load<std::int16_t>(in);
        case 4: return load<std::int32_t>(in);
        default: return load<std::int64_t>(in);
    }
}

/// A field as the file declares it.
struct PcdField {
    std::string name;
    char type = 'F';
    int size = 4;
    int count = 1;
    const ReturnField* target = nullptr;  ///< nullptr: a field a Return has no place for
};

enum class DataFormat { ascii, binary };

struct PcdHeader {
    std::vector<PcdField> fields;
    std::uint64_t points = 0;
    DataFormat format = DataFormat::binary;
    std::size_t data_offset = 0;  ///< first byte after the DATA line
};

std::vector<std::string> split_words(std::string_view line) {
    std::istringstream in{std::string(line)};
    return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

class HeaderParser {
public:
    HeaderParser(std::string file, const std::string& bytes) : file_(std::move(file)), bytes_(bytes) {}

    PcdHeader parse() {
        std::size_t pos = 0;
        std::optional<DataFormat> format;
        while (!format) {
            if (pos >= bytes_.size()) fail("DATA", "the header has no DATA line");
            std::size_t end = bytes_.find('\n', pos);
            if (end == std::string::npos) end = bytes_.size();
            std::string_view line(bytes_.data() + pos, end - pos);
            pos = end + 1;
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            const auto words = split_words(line);
            if (words.empty() || words[0].front() == '#') continue;
            const std::string& keyword = words[0];
            const std::vector<std::string> values(words.begin() + 1, words.end());
            if (keyword == "DATA") {
                format = data_format(values);
            } else {
                read_keyword(keyword, values);
            }
        }
        return finish(*format, std::min(pos, bytes_.size()));
    }

private:
    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw InputError(file_, field, problem);
    }

    std::uint64_t whole_number(const std::string& keyword, const std::string& word) const {
        std::uint64_t value = 0;
        const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (ec != std::errc() || end != word.data() + word.size()) {
            fail(keyword, "expected a whole number, found '" + word + "'");
        }
        return value;
    }

    std::uint64_t single_number(const std::string& keyword, const std::vector<std::string>& values) const {
        if (values.size() != 1) fail(keyword, "expected one value, found " + std::to_string(values.size()));
        return whole_number(keyword, values[0]);
    }

    DataFormat data_format(const std::vector<std::string>& values) const {
        if (values.size() == 1 && values[0] == "binary") return DataFormat::binary;
        if (values.size() == 1 && values[0] == "ascii") return DataFormat::ascii;
        if (values.size() == 1 && values[0] == "binary_compressed") {
            fail("DATA", "binary_compressed is not supported (pcl_convert_pcd_ascii_binary converts it)");
        }
        fail("DATA", "expected ascii or binary");
    }

    void read_keyword(const std::string& keyword, const std::vector<std::string>& values) {
        if (keyword == "VERSION") {
            // Every version since 0.5 lays out data the same way; only the header differs.
        } else if (keyword == "FIELDS" || keyword == "COLUMNS") {  // COLUMNS: PCD before v0.7
            if (values.empty()) fail(keyword, "no fields");
            names_ = values;
        } else if (keyword == "SIZE") {
            sizes_ = values;
        } else if (keyword == "TYPE") {
            types_ = values;
        } else if (keyword == "COUNT") {
            counts_ = values;
        } else if (keyword == "WIDTH") {
            width_ = single_number(keyword, values);
        } else if (keyword == "HEIGHT") {
            height_ = single_number(keyword, values);
        } else if (keyword == "POINTS") {
            points_ = single_number(keyword, values);
        } else if (keyword == "VIEWPOINT") {
            // The cloud's points are read as they are; where it was taken from does not move them.
        } else {
            fail("header", "unknown keyword '" + keyword + "'");
        }
    }

    PcdHeader finish(DataFormat format, std::size_t data_offset) const {
        if (names_.empty()) fail("FIELDS", "the header has no FIELDS line");
        const std::size_t n = names_.size();
        if (sizes_.size() != n) fail("SIZE", std::to_string(sizes_.size()) + " sizes for " + std::to_string(n) + " fields");
        if (types_.size() != n) fail("TYPE", std::to_string(types_.size()) + " types for " + std::to_string(n) + " fields");
        if (!counts_.empty() && counts_.size() != n) {
            fail("COUNT", std::to_string(counts_.size()) + " counts for " + std::to_string(n) + " fields");
        }
        if (!width_) fail("WIDTH", "the header has no WIDTH line");

        PcdHeader header;
        header.format = format;
        header.data_offset = data_offset;
        const std::uint64_t height = height_.value_or(1);
        if (height != 0 && *width_ > std::numeric_limits<std::uint64_t>::max() / height) fail("WIDTH", "too large");
        header.points = *width_ * height;
        if (points_ && *points_ != header.points) {
            fail("POINTS", std::to_string(*points_) + " points, but WIDTH x HEIGHT = " + std::to_string(header.points));
        }
        for (std::size_t i = 0; i < n; ++i) header.fields.push_back(field(i));
        for (std::string_view axis : {"x", "y", "z"}) {
            bool found = false;
            for (const auto& f : header.fields) found = found || f.name == axis;
            if (!found) fail("FIELDS", "no '" + std::string(axis) + "' field");
        }
        return header;
    }

    PcdField field(std::size_t i) const {
        PcdField f;
        f.name = names_[i];
        const std::string what = "field '" + f.name + "'";
        if (types_[i].size() != 1 || std::string_view("FUI").find(types_[i][0]) == std::string_view::npos) {
            fail("TYPE", what + ": '" + types_[i] + "' is not F, U or I");
        }
        f.type = types_[i][0];
        f.size = static_cast<int>(whole_number("SIZE", sizes_[i]));
        const bool valid_size = f.type == 'F' ? (f.size == 4 || f.size == 8)
                                              : (f.size == 1 || f.size == 2 || f.size == 4 || f.size == 8);
        if (!valid_size) fail("SIZE", what + ": size " + sizes_[i] + " is not defined for TYPE " + types_[i]);
        f.count = counts_.empty() ? 1 : static_cast<int>(whole_number("COUNT", counts_[i]));
        if (f.count < 1) fail("COUNT", what + ": count must be at least 1");
        for (const auto& target : kReturnFields) {
            if (target.name == f.name) f.target = &target;
        }
        if (f.target && f.count != 1) fail("COUNT", what + ": expected COUNT 1, found " + counts_[i]);
        return f;
    }

    std::string file_;
    const std::string& bytes_;
    std::vector<std::string> names_, sizes_, types_, counts_;
    std::optional<std::uint64_t> width_, height_, points_;
};

class PointReader {
public:
    PointReader(std::string file, const PcdHeader& header) : file_(std::move(file)), header_(header) {}

    /// Stores `value` of field `f` of point `point`; integer fields must hold it exactly.
    void set(Return& r, const PcdField& f, double value, std::uint64_t point) const {
        if (f.target->type == 'U') {
            const double max = std::ldexp(1.0, 8 * f.target->size) - 1.0;
            if (!(value >= 0.0 && value <= max && value == std::floor(value))) {
                throw InputError(file_, "DATA",
                                 "point " + std::to_string(point) + ": " + f.name + " = " +
                                     std::to_string(value) + " is not a whole number in [0, " +
                                     std::to_string(static_cast<std::uint64_t>(max)) + "]");
            }
        }
        f.target->set(r, value);
    }

    static bool has_position(const Return& r) { return !r.position_sensor.array().isNaN().any(); }

    std::vector<Return> binary(const std::string& bytes) const {
        std::size_t step = 0;
        for (const auto& f : header_.fields) step += static_cast<std::size_t>(f.size) * static_cast<std::size_t>(f.count);
        const std::size_t available = bytes.size() - header_.data_offset;
        if (header_.points > available / step) {
            throw InputError(file_, "DATA",
                             "truncated: " + std::to_string(header_.points) + " points need " +
                                 std::to_string(header_.points * step) + " bytes, the file has " +
                                 std::to_string(available));
        }
        std::vector<Return> out;
        out.reserve(header_.points);
        const char* p = bytes.data() + header_.data_offset;
        for (std::uint64_t i = 0; i < header_.points; ++i) {
            Return r;
            for (const auto& f : header_.fields) {
                if (f.target) set(r, f, decode(f.type, f.size, p), i);
                p += static_cast<std::size_t>(f.size) * static_cast<std::size_t>(f.count);
            }
            if (has_position(r)) out.push_back(r);
        }
        return out;
    }

    std::vector<Return> ascii(const std::string& bytes) const {
        std::istringstream in(bytes.substr(header_.data_offset));
        std::vector<Return> out;
        std::string line;
        std::uint64_t point = 0;
        while (point < header_.points && std::getline(in, line)) {
            const auto words = split_words(line);
            if (words.empty()) continue;
            Return r;
            std::size_t w = 0;
            for (const auto& f : header_.fields) {
                if (w + static_cast<std::size_t>(f.count) > words.size()) {
                    throw InputError(file_, "DATA", "point " + std::to_string(point) + ": too few values");
                }
                if (f.target) set(r, f, number(words[w], point), point);
                w += static_cast<std::size_t>(f.count);
            }
            if (w != words.size()) throw InputError(file_, "DATA", "point " + std::to_string(point) + ": too many values");
            if (has_position(r)) out.push_back(r);
            ++point;
        }
        if (point < header_.points) {
            throw InputError(file_, "DATA",
                             "truncated: " + std::to_string(header_.points) + " points declared, " +
                                 std::to_string(point) + " found");
        }
        return out;
    }

private:
    double number(const std::string& word, std::uint64_t point) const {
        double value = 0.0;
        const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (ec != std::errc() || end != word.data() + word.size()) {
            throw InputError(file_, "DATA", "point " + std::to_string(point) + ": '" + word + "' is not a number");
        }
        return value;
    }

    std::string file_;
    const PcdHeader& header_;
};

}  // namespace

void write_frame_pcd(const std::filesystem::path& path, const Frame& frame) {
    constexpr std::size_t step = point_step_bytes();
    const std::size_t n = frame.returns.size();
    std::string fields, sizes, types, counts;
    for (const auto& f : kReturnFields) {
        fields += ' ' + std::string(f.name);
        sizes += ' ' + std::to_string(f.size);
        types += std::string(" ") + f.type;
        counts += " 1";
    }
    const std::string header = "# .PCD v0.7 - Point Cloud Data file format\n"
                               "VERSION 0.7\n"
                               "FIELDS" + fields + "\nSIZE" + sizes + "\nTYPE" + types + "\nCOUNT" + counts +
                               "\nWIDTH " + std::to_string(n) +
                               "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(n) +
                               "\nDATA binary\n";
    std::vector<char> data(n * step);
    char* p = data.data();
    for (const auto& r : frame.returns) {
        for (const auto& f : kReturnFields) {
            encode(f.type, f.size, f.get(r), p);
            p += f.size;
        }
    }
    AtomicFile out(path);
    out.stream().write(header.data(), static_cast<std::streamsize>(header.size()));
    out.stream().write(data.data(), static_cast<std::streamsize>(data.size()));
    out.commit();
}

std::vector<Return> read_frame_pcd(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file, "(file)", "cannot open the point cloud");
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw InputError(file, "(file)", "cannot read the point cloud");

    const PcdHeader header = HeaderParser(file, bytes).parse();
    const PointReader reader(file, header);
    return header.format == DataFormat::binary ? reader.binary(bytes) : reader.ascii(bytes);
}

}  // namespace ladarsim
