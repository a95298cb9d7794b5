#include "ladarsim/scene/ply_file.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "ladarsim/core/input_error.h"

namespace ladarsim::scene {

namespace {

enum class Encoding { ascii, little_endian, big_endian };

struct PlyType {
    int bytes = 0;
    bool is_signed = false, is_float = false;
};

std::optional<PlyType> ply_type(const std::string& name) {
    if (name == "char" || name == "int8") return PlyType{1, true, false};
    if (name == "uchar" || name == "uint8") return PlyType{1, false, false};
    if (name == "short" || name == "int16") return PlyType{2, true, false};
    if (name == "ushort" || name == "uint16") return PlyType{2, false, false};
    if (name == "int" || name == "int32") return PlyType{4, true, false};
    if (name == "uint" || name == "uint32") return PlyType{4, false, false};
    if (name == "float" || name == "float32") return PlyType{4, true, true};
    if (name == "double" || name == "float64") return PlyType{8, true, true};
    return std::nullopt;
}

struct PlyProperty {
    std::string name;
    PlyType type;
    std::optional<PlyType> list_count;  ///< set for `property list COUNT_TYPE TYPE NAME`
};

struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    Encoding encoding = Encoding::ascii;
    std::vector<PlyElement> elements;
};

/// Reads one element's values from the body, whatever its encoding.
class BodyReader {
public:
    BodyReader(std::istream& in, Encoding encoding, const std::string& file) : in_(in), encoding_(encoding), file_(file) {}

    double scalar(const PlyType& type, const std::string& element) {
        if (encoding_ == Encoding::ascii) {
            double v = 0.0;
            if (!(in_ >> v)) fail(element);
            return v;
        }
        unsigned char bytes[8];
        if (!in_.read(reinterpret_cast<char*>(bytes), type.bytes)) fail(element);
        if ((encoding_ == Encoding::big_endian) != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + type.bytes);
        return decode(bytes, type);
    }

private:
    static double decode(const unsigned char* b, const PlyType& t) {
        const auto as = [b]<typename T>(T v) {
            std::memcpy(&v, b, sizeof v);
            return static_cast<double>(v);
        };
        if (t.is_float) return t.bytes == 4 ? as(float{}) : as(double{});
        switch (t.bytes) {
            case 1: return t.is_signed ? as(std::int8_t{}) : as(std::uint8_t{});
            case 2: return t.is_signed ? as(std::int16_t{}) : as(std::uint16_t{});
            default: return t.is_signed ? as(std::int32_t{}) : as(std::uint32_t{});
        }
    }
    [[noreturn]] void fail(const std::string& element) const {
        throw InputError(file_, "element " + element, "the data is cut short or unreadable (fewer values than the header says)");
    }

    std::istream& in_;
    Encoding encoding_;
    const std::string& file_;
};

PlyHeader read_header(std::istream& in, const std::string& file) {
    std::string line;
    if (!std::getline(in, line) || line.substr(0, 3) != "ply") throw InputError(file, "(file)", "not a PLY file (no 'ply' line first)");
    PlyHeader header;
    bool format_seen = false;
    for (int number = 2; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        const std::string where = "header line " + std::to_string(number);
        if (keyword == "end_header") {
            if (!format_seen) throw InputError(file, where, "end_header before any 'format' line");
            return header;
        }
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            std::string format;
            words >> format;
            if (format == "ascii") header.encoding = Encoding::ascii;
            else if (format == "binary_little_endian") header.encoding = Encoding::little_endian;
            else if (format == "binary_big_endian") header.encoding = Encoding::big_endian;
            else throw InputError(file, where, "unknown format '" + format + "'");
            format_seen = true;
        } else if (keyword == "element") {
            PlyElement element;
            long long count = -1;
            if (!(words >> element.name >> count) || count < 0) throw InputError(file, where, "expected 'element NAME COUNT'");
            element.count = static_cast<std::size_t>(count);
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) throw InputError(file, where, "a property before any element");
            std::string type_name;
            words >> type_name;
            PlyProperty property;
            if (type_name == "list") {
                std::string count_type;
                words >> count_type >> type_name;
                property.list_count = ply_type(count_type);
                if (!property.list_count || property.list_count->is_float)
                    throw InputError(file, where, "a list's count type must be an integer type, not '" + count_type + "'");
            }
            const std::optional<PlyType> type = ply_type(type_name);
            if (!type || !(words >> property.name)) throw InputError(file, where, "expected 'property TYPE NAME' with a PLY type, not '" + line + "'");
            property.type = *type;
            header.elements.back().properties.push_back(std::move(property));
        } else {
            throw InputError(file, where, "unknown keyword '" + keyword + "'");
        }
    }
    throw InputError(file, "(header)", "the header has no end_header line");
}

}  // namespace

std::optional<std::size_t> PlyVertices::property(std::string_view name) const {
    const auto it = std::find(properties.begin(), properties.end(), name);
    if (it == properties.end()) return std::nullopt;
    return static_cast<std::size_t>(it - properties.begin());
}

PlyVertices read_ply(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file, "(file)", "cannot be opened");
    const PlyHeader header = read_header(in, file);
    const auto vertex = std::find_if(header.elements.begin(), header.elements.end(), [](const PlyElement& e) { return e.name == "vertex"; });
    if (vertex == header.elements.end()) throw InputError(file, "element vertex", "the file has no vertex element");
    BodyReader body(in, header.encoding, file);
    PlyVertices vertices;
    for (const PlyProperty& p : vertex->properties)
        if (!p.list_count) vertices.properties.push_back(p.name);
    vertices.count = vertex->count;
    vertices.values.reserve(std::min<std::size_t>(vertex->count, std::size_t{1} << 28) * vertices.properties.size());
    for (auto element = header.elements.begin(); element != std::next(vertex); ++element) {
        const bool keep = element == vertex;
        for (std::size_t i = 0; i < element->count; ++i) {
            for (const PlyProperty& p : element->properties) {
                if (!p.list_count) {
                    const double v = body.scalar(p.type, element->name);
                    if (keep) vertices.values.push_back(v);
                    continue;
                }
                const double n = body.scalar(*p.list_count, element->name);
                if (n < 0) throw InputError(file, "element " + element->name, "a list has a negative length");
                for (double k = 0; k < n; ++k) body.scalar(p.type, element->name);
            }
        }
    }
    return vertices;
}

}  // namespace ladarsim::scene
