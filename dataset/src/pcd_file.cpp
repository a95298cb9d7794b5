#include "ladarsim/dataset/pcd_file.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/lzf.h"

namespace ladarsim {

// PCD binary data is the writer's memory image, and every PCD reader assumes little-endian.
static_assert(std::endian::native == std::endian::little, "PCD binary I/O assumes a little-endian host");

namespace {

template <typename T>
double load(const char* in) {
    T v;
    std::memcpy(&v, in, sizeof v);  // fields need not be aligned
    return static_cast<double>(v);
}

template <typename T>
void store(char* out, double value) {
    const T v = static_cast<T>(value);
    std::memcpy(out, &v, sizeof v);
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_blank(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_blank(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

enum class DataFormat { ascii, binary, binary_compressed };

struct PcdHeader {
    std::vector<PcdField> fields;
    std::uint64_t width = 0;
    std::uint64_t height = 0;
    DataFormat format = DataFormat::binary;
    std::size_t data_offset = 0;  ///< first byte after the DATA line
};

/// Whether `word` is text a person could read in a message (a garbage file's header is not).
bool is_text(const std::string& word) {
    return std::all_of(word.begin(), word.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
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
            const auto words = split_words(std::string_view(bytes_).substr(pos, end - pos));
            pos = end + 1;
            if (words.empty() || words[0].front() == '#') continue;
            const std::string keyword(words[0]);
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
            fail(keyword, is_text(word) ? "expected a whole number, found '" + word.substr(0, 32) + "'"
                                        : "expected a whole number, found binary data: not a PCD point cloud");
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
        if (values.size() == 1 && values[0] == "binary_compressed") return DataFormat::binary_compressed;
        fail("DATA", "expected ascii, binary or binary_compressed");
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
            fail("header", is_text(keyword) ? "unknown keyword '" + keyword.substr(0, 32) + "'"
                                            : "binary data where the header should be: not a PCD point cloud");
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
        PcdHeader header;
        header.format = format;
        header.data_offset = data_offset;
        // Before v0.7 a cloud was a list: POINTS alone gives its length.
        if (!width_ && !height_ && points_) {
            header.width = *points_;
            header.height = 1;
        } else if (!width_) {
            fail("WIDTH", "the header has no WIDTH line");
        } else {
            header.width = *width_;
            header.height = height_.value_or(1);
        }
        if (header.height != 0 && header.width > std::numeric_limits<std::uint64_t>::max() / header.height) {
            fail("WIDTH", "too large");
        }
        const std::uint64_t points = header.width * header.height;
        if (points_ && *points_ != points) {
            fail("POINTS", std::to_string(*points_) + " points, but WIDTH x HEIGHT = " + std::to_string(points));
        }
        for (std::size_t i = 0; i < n; ++i) header.fields.push_back(field(i));
        for (std::string_view axis : {"x", "y", "z"}) {
            bool found = false;
            for (const auto& f : header.fields) found = found || f.name == axis;
            if (!found) fail("FIELDS", "no '" + std::string(axis) + "' field: a point cloud needs x, y and z");
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
        const std::uint64_t size = whole_number("SIZE", sizes_[i]);
        const bool valid_size = f.type == 'F' ? (size == 4 || size == 8) : (size == 1 || size == 2 || size == 4 || size == 8);
        if (!valid_size) fail("SIZE", what + ": size " + sizes_[i] + " is not defined for TYPE " + types_[i]);
        f.size = static_cast<int>(size);
        // Thousands of elements a point is more than any descriptor PCL has (FPFH: 33, VFH: 308).
        const std::uint64_t count = counts_.empty() ? 1 : whole_number("COUNT", counts_[i]);
        if (count < 1 || count > 65535) fail("COUNT", what + ": count must be in [1, 65535]");
        f.count = static_cast<int>(count);
        return f;
    }

    std::string file_;
    const std::string& bytes_;
    std::vector<std::string> names_, sizes_, types_, counts_;
    std::optional<std::uint64_t> width_, height_, points_;
};

class DataReader {
public:
    DataReader(std::string file, const PcdHeader& header, const std::string& bytes)
        : file_(std::move(file)), header_(header), data_(std::string_view(bytes).substr(header.data_offset)) {}

    PcdCloud read() const {
        switch (header_.format) {
            case DataFormat::ascii: return ascii();
            case DataFormat::binary: return binary();
            default: return binary_compressed();
        }
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, "DATA", problem); }

    PcdCloud empty_cloud() const { return PcdCloud(header_.fields, header_.width, header_.height); }

    std::uint64_t points() const { return header_.width * header_.height; }

    std::uint64_t point_step() const {
        std::uint64_t step = 0;
        for (const auto& f : header_.fields) step += static_cast<std::uint64_t>(f.size) * static_cast<std::uint64_t>(f.count);
        return step;
    }

    PcdCloud binary() const {
        // Checked before a cloud of that size is made.
        if (points() > data_.size() / point_step()) {
            fail("truncated: " + std::to_string(points()) + " points need " + std::to_string(points() * point_step()) +
                 " bytes, the file has " + std::to_string(data_.size()));
        }
        PcdCloud cloud = empty_cloud();
        // An empty cloud's buffer may be a null pointer, which memcpy must not get even for 0 bytes.
        if (!cloud.data().empty()) std::memcpy(cloud.data().data(), data_.data(), cloud.data().size());
        return cloud;
    }

    /// PCL's layout: two little-endian U4 sizes (compressed, uncompressed), then the LZF stream
    /// of every point's first field, then every point's second field, and so on.
    PcdCloud binary_compressed() const {
        const std::uint64_t points = this->points(), step = point_step();
        if (points == 0) return empty_cloud();
        if (data_.size() < 8) fail("truncated: no compressed sizes");
        const auto compressed = static_cast<std::uint64_t>(load<std::uint32_t>(data_.data()));
        const auto uncompressed = static_cast<std::uint64_t>(load<std::uint32_t>(data_.data() + 4));
        if (points > std::numeric_limits<std::uint32_t>::max() / step || uncompressed != points * step) {
            fail("binary_compressed: " + std::to_string(uncompressed) + " bytes uncompressed, but the header's " +
                 std::to_string(points) + " points take " + std::to_string(points * step));
        }
        if (compressed > data_.size() - 8) {
            fail("truncated: " + std::to_string(compressed) + " compressed bytes declared, the file has " +
                 std::to_string(data_.size() - 8));
        }
        // A three-byte back reference writes at most 264 bytes: no valid stream expands further,
        // and a corrupt size must not allocate gigabytes.
        if (uncompressed > 88 * compressed) fail("binary_compressed: the compressed data is corrupt");
        std::vector<unsigned char> fields_after_fields(uncompressed);
        const auto* in = reinterpret_cast<const unsigned char*>(data_.data() + 8);
        if (lzf_decompress({in, compressed}, fields_after_fields) != uncompressed) {
            fail("binary_compressed: the compressed data is corrupt");
        }
        PcdCloud cloud = empty_cloud();
        std::size_t offset = 0;
        for (const auto& f : header_.fields) {
            const std::size_t width = static_cast<std::size_t>(f.size) * static_cast<std::size_t>(f.count);
            const unsigned char* block = fields_after_fields.data() + points * offset;
            for (std::uint64_t i = 0; i < points; ++i) {
                std::memcpy(cloud.data().data() + i * step + offset, block + i * width, width);
            }
            offset += width;
        }
        return cloud;
    }

    PcdCloud ascii() const {
        const std::uint64_t points = this->points();
        std::size_t elements = 0;
        for (const auto& f : header_.fields) elements += static_cast<std::size_t>(f.count);
        // Every line counted first, so that a header promising more points or values than the
        // file holds fails before a cloud of that size is made.
        std::vector<std::string_view> lines;
        std::size_t pos = 0;
        while (lines.size() < points && pos < data_.size()) {
            std::size_t end = data_.find('\n', pos);
            if (end == std::string_view::npos) end = data_.size();
            const std::string_view line = data_.substr(pos, end - pos);
            pos = end + 1;
            const std::size_t words = split_words(line).size();
            if (words == 0) continue;
            if (words != elements) {
                const std::string problem = words < elements ? ": too few values" : ": too many values";
                fail("point " + std::to_string(lines.size()) + problem);
            }
            lines.push_back(line);
        }
        if (lines.size() < points) {
            fail("truncated: " + std::to_string(points) + " points declared, " + std::to_string(lines.size()) + " found");
        }
        PcdCloud cloud = empty_cloud();
        for (std::uint64_t i = 0; i < points; ++i) {
            const auto words = split_words(lines[i]);
            std::size_t w = 0;
            for (std::size_t f = 0; f < header_.fields.size(); ++f) {
                const PcdField& field = header_.fields[f];
                for (int e = 0; e < field.count; ++e) cloud.set(i, f, e, number(field, words[w++], i));
            }
        }
        return cloud;
    }

    /// A value as text, of its field's TYPE and SIZE. Floats are parsed at their own precision
    /// (as PCL does), not rounded twice through double.
    double number(const PcdField& field, std::string_view word, std::uint64_t point) const {
        if (word.size() > 1 && word.front() == '+') word.remove_prefix(1);
        double value = 0.0;
        std::from_chars_result parsed{};
        if (field.type == 'F' && field.size == 4) {
            float f = 0.0f;
            parsed = std::from_chars(word.data(), word.data() + word.size(), f);
            value = f;
        } else {
            parsed = std::from_chars(word.data(), word.data() + word.size(), value);
        }
        const bool complete = parsed.ec == std::errc() && parsed.ptr == word.data() + word.size();
        if (!complete || !pcd_type_holds(field.type, field.size, value)) {
            fail("point " + std::to_string(point) + ": " + field.name + " '" + std::string(word) + "' is not a number of TYPE " +
                 field.type + " SIZE " + std::to_string(field.size));
        }
        return value;
    }

    std::string file_;
    const PcdHeader& header_;
    std::string_view data_;
};

}  // namespace

bool pcd_type_holds(char type, int size, double value) {
    if (type == 'F') return true;
    const int bits = 8 * size;
    const double lo = type == 'U' ? 0.0 : -std::ldexp(1.0, bits - 1);
    const double end = type == 'U' ? std::ldexp(1.0, bits) : std::ldexp(1.0, bits - 1);  // exclusive
    return value >= lo && value < end && value == std::floor(value);
}

PcdCloud::PcdCloud(std::vector<PcdField> fields, std::uint64_t width, std::uint64_t height)
    : fields_(std::move(fields)), width_(width), height_(height) {
    for (const auto& f : fields_) {
        offsets_.push_back(point_step_);
        point_step_ += static_cast<std::size_t>(f.size) * static_cast<std::size_t>(f.count);
    }
    data_.assign(points() * point_step_, 0);
}

std::optional<std::size_t> PcdCloud::field(std::string_view name) const {
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        if (fields_[i].name == name) return i;
    }
    return std::nullopt;
}

const char* PcdCloud::at(std::uint64_t point, std::size_t field, int element) const {
    return data_.data() + point * point_step_ + offsets_[field] +
           static_cast<std::size_t>(element) * static_cast<std::size_t>(fields_[field].size);
}

char* PcdCloud::at(std::uint64_t point, std::size_t field, int element) {
    return const_cast<char*>(std::as_const(*this).at(point, field, element));
}

double PcdCloud::value(std::uint64_t point, std::size_t field, int element) const {
    const PcdField& f = fields_[field];
    const char* in = at(point, field, element);
    if (f.type == 'F') return f.size == 4 ? load<float>(in) : load<double>(in);
    if (f.type == 'U') {
        switch (f.size) {
            case 1: return load<std::uint8_t>(in);
            case 2: return load<std::uint16_t>(in);
            case 4: return load<std::uint32_t>(in);
            default: return load<std::uint64_t>(in);
        }
    }
    switch (f.size) {
        case 1: return load<std::int8_t>(in);
        case 2: return load<std::int16_t>(in);
        case 4: return load<std::int32_t>(in);
        default: return load<std::int64_t>(in);
    }
}

void PcdCloud::set(std::uint64_t point, std::size_t field, int element, double value) {
    const PcdField& f = fields_[field];
    char* out = at(point, field, element);
    if (f.type == 'F') {
        f.size == 4 ? store<float>(out, value) : store<double>(out, value);
    } else if (f.type == 'U') {
        switch (f.size) {
            case 1: store<std::uint8_t>(out, value); break;
            case 2: store<std::uint16_t>(out, value); break;
            case 4: store<std::uint32_t>(out, value); break;
            default: store<std::uint64_t>(out, value); break;
        }
    } else {
        switch (f.size) {
            case 1: store<std::int8_t>(out, value); break;
            case 2: store<std::int16_t>(out, value); break;
            case 4: store<std::int32_t>(out, value); break;
            default: store<std::int64_t>(out, value); break;
        }
    }
}

PcdCloud read_pcd(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file, "(file)", "cannot open the point cloud");
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw InputError(file, "(file)", "cannot read the point cloud");
    const PcdHeader header = HeaderParser(file, bytes).parse();
    return DataReader(file, header, bytes).read();
}

void write_pcd(const std::filesystem::path& path, const PcdCloud& cloud) {
    std::string fields, sizes, types, counts;
    for (const auto& f : cloud.fields()) {
        fields += ' ' + f.name;
        sizes += ' ' + std::to_string(f.size);
        types += std::string(" ") + f.type;
        counts += ' ' + std::to_string(f.count);
    }
    const std::string header = "# .PCD v0.7 - Point Cloud Data file format\n"
                               "VERSION 0.7\n"
                               "FIELDS" + fields + "\nSIZE" + sizes + "\nTYPE" + types + "\nCOUNT" + counts +
                               "\nWIDTH " + std::to_string(cloud.width()) + "\nHEIGHT " + std::to_string(cloud.height()) +
                               "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(cloud.points()) + "\nDATA binary\n";
    AtomicFile out(path);
    out.stream().write(header.data(), static_cast<std::streamsize>(header.size()));
    out.stream().write(cloud.data().data(), static_cast<std::streamsize>(cloud.data().size()));
    out.commit();
}

}  // namespace ladarsim
