#include "ladarsim/dataset/frame_pcd.h"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/pcd_file.h"

namespace ladarsim {

namespace {

/// One Return member as a PCD field. Values pass through double, which holds every F4, F8, U1,
/// U2 and U4 value exactly, so one table drives both the writer and the reader.
struct ReturnField {
    std::string_view name;
    char type;  ///< PCD TYPE: F float, U unsigned
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

constexpr std::array<ReturnField, 16> kReturnFields{{
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
    {"saturated", 'U', 1, get_member<&Return::saturated>, set_member<&Return::saturated>},
}};

/// A Return field and where the cloud holds it.
struct FieldSource {
    const ReturnField* target;
    std::size_t field;
};

}  // namespace

PcdCloud frame_pcd_cloud(const std::vector<Return>& returns) {
    std::vector<PcdField> fields;
    for (const auto& f : kReturnFields) fields.push_back({std::string(f.name), f.type, f.size, 1});
    PcdCloud cloud(std::move(fields), returns.size(), 1);
    for (std::size_t i = 0; i < returns.size(); ++i) {
        for (std::size_t f = 0; f < kReturnFields.size(); ++f) {
            cloud.set(i, f, 0, kReturnFields[f].get(returns[i]));
        }
    }
    return cloud;
}

void write_frame_pcd(const std::filesystem::path& path, const Frame& frame) {
    write_pcd(path, frame_pcd_cloud(frame.returns));
}

std::vector<Return> read_frame_pcd(const std::filesystem::path& path) {
    const std::string file = path.string();
    const PcdCloud cloud = read_pcd(path);
    std::vector<FieldSource> sources;
    for (const auto& target : kReturnFields) {
        const std::optional<std::size_t> f = cloud.field(target.name);
        if (!f) continue;
        const PcdField& field = cloud.fields()[*f];
        if (field.count != 1) {
            throw InputError(file, "COUNT",
                             "field '" + field.name + "': expected COUNT 1, found " + std::to_string(field.count));
        }
        sources.push_back({&target, *f});
    }
    std::vector<Return> out;
    out.reserve(cloud.points());
    for (std::uint64_t i = 0; i < cloud.points(); ++i) {
        Return r;
        for (const auto& s : sources) {
            const double value = cloud.value(i, s.field);
            if (!pcd_type_holds(s.target->type, s.target->size, value)) {
                throw InputError(file, "DATA",
                                 "point " + std::to_string(i) + ": " + std::string(s.target->name) + " = " +
                                     std::to_string(value) + " does not fit a Return's TYPE " + s.target->type +
                                     " SIZE " + std::to_string(s.target->size));
            }
            s.target->set(r, value);
        }
        if (!r.position_sensor.array().isNaN().any()) out.push_back(r);
    }
    return out;
}

}  // namespace ladarsim
