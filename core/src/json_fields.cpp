#include "ladarsim/core/json_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ladarsim/core/input_error.h"

namespace ladarsim {

namespace {
const char* type_name(const nlohmann::json& j) { return j.type_name(); }

/// Levenshtein distance: letters inserted, deleted or replaced.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// Whether `typo` is likely a misspelling of `key`: one letter missing, extra or wrong. Only one:
/// keys that are two apart are often both valid ("beams_az", "beams_el"), and short keys ("x",
/// "y") are never taken for each other.
bool misspells(const std::string& typo, const std::string& key) {
    return key.size() >= 5 && edit_distance(typo, key) == 1;
}
}  // namespace

JsonFields::JsonFields(const nlohmann::json& object, std::string file, std::string path)
    : object_(object), file_(std::move(file)), path_(std::move(path)) {
    if (!object_.is_object()) {
        throw InputError(file_, path_.empty() ? "(top level)" : path_,
                         std::string("expected an object, found ") + type_name(object_));
    }
}

bool JsonFields::has(const std::string& key) const { return object_.contains(key); }

bool JsonFields::null(const std::string& key) {
    const auto it = object_.find(key);
    if (it == object_.end() || !it->is_null()) return false;
    used_.insert(key);
    return true;
}

std::string JsonFields::path_of(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
}

void JsonFields::fail(const std::string& key, const std::string& problem) const {
    throw InputError(file_, key.empty() ? path_ : path_of(key), problem);
}

const nlohmann::json& JsonFields::get(const std::string& key) {
    auto it = object_.find(key);
    if (it == object_.end()) {
        // A misspelt required key: the typo is what the user wrote, so name it.
        for (const auto& item : object_.items())
            if (!used_.count(item.key()) && misspells(item.key(), key))
                fail(item.key(), "unknown key; did you mean \"" + key + "\"?");
        fail(key, "required field is missing");
    }
    used_.insert(key);
    return *it;
}

double JsonFields::number(const std::string& key, double min, double max) {
    const auto& v = get(key);
    if (!v.is_number()) fail(key, std::string("expected a number, found ") + type_name(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "must be finite");
    if (x < min || x > max) {
        fail(key, "value " + nlohmann::json(x).dump() + " is outside [" + nlohmann::json(min).dump() +
                      ", " + nlohmann::json(max).dump() + "]");
    }
    return x;
}

double JsonFields::number(const std::string& key, double min, double max, double fallback) {
    return has(key) ? number(key, min, max) : fallback;
}

long long JsonFields::integer(const std::string& key, long long min, long long max) {
    const auto& v = get(key);
    if (!v.is_number_integer()) fail(key, std::string("expected a whole number, found ") + v.dump());
    // nlohmann keeps 2^63..2^64-1 as unsigned; get<long long> would wrap them to negatives.
    const bool fits = !v.is_number_unsigned() ||
                      v.get<unsigned long long>() <= static_cast<unsigned long long>(std::numeric_limits<long long>::max());
    const long long x = fits ? v.get<long long>() : 0;
    if (!fits || x < min || x > max) {
        fail(key, "value " + v.dump() + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    return x;
}

long long JsonFields::integer(const std::string& key, long long min, long long max, long long fallback) {
    return has(key) ? integer(key, min, max) : fallback;
}

bool JsonFields::boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const auto& v = get(key);
    if (!v.is_boolean()) fail(key, std::string("expected true or false, found ") + type_name(v));
    return v.get<bool>();
}

std::string JsonFields::string(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_string()) fail(key, std::string("expected a string, found ") + type_name(v));
    return v.get<std::string>();
}

std::string JsonFields::string(const std::string& key, const std::string& fallback) {
    return has(key) ? string(key) : fallback;
}

std::string JsonFields::choice(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) {
    const std::string value = string(key, fallback);
    for (const auto& a : allowed) {
        if (a == value) return value;
    }
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(key, "\"" + value + "\" is not one of: " + list);
}

Eigen::Vector3d JsonFields::vec3(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
    Eigen::Vector3d out;
    for (int i = 0; i < 3; ++i) {
        if (!v[i].is_number()) fail(key, "expected an array of 3 numbers");
        out[i] = v[i].get<double>();
        if (!std::isfinite(out[i])) fail(key, "must be finite");
    }
    return out;
}

Eigen::Vector3d JsonFields::vec3(const std::string& key, const Eigen::Vector3d& fallback) {
    return has(key) ? vec3(key) : fallback;
}

const nlohmann::json& JsonFields::object(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_object()) fail(key, std::string("expected an object, found ") + type_name(v));
    return v;
}

const nlohmann::json& JsonFields::array(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_array()) fail(key, std::string("expected an array, found ") + type_name(v));
    return v;
}

void JsonFields::reject_unknown_keys() const {
    for (const auto& item : object_.items()) {
        if (!used_.count(item.key())) fail(item.key(), "unknown key");
    }
}

}  // namespace ladarsim
