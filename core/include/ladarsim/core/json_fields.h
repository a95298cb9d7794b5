#pragma once
// Reading one JSON object of a scenario file: typed, range-checked fields, and every key
// that nobody asked for reported by name (typos must not be silently ignored).
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace ladarsim {

class JsonFields {
public:
    /// `path` is the field path of `object` inside `file`, e.g. "objects[2].trajectory".
    /// Throws InputError if `object` is not a JSON object.
    JsonFields(const nlohmann::json& object, std::string file, std::string path);

    bool has(const std::string& key) const;
    /// Whether the key holds null; if so it is read (marked as used), else left alone.
    bool null(const std::string& key);
    /// Full field path of a key, for messages: "objects[2].trajectory.speed_mps".
    std::string path_of(const std::string& key) const;
    const std::string& file() const { return file_; }

    /// A finite number in [min, max]; required.
    double number(const std::string& key, double min, double max);
    /// Same, with a default when the key is absent.
    double number(const std::string& key, double min, double max, double fallback);
    /// A whole number in [min, max].
    long long integer(const std::string& key, long long min, long long max);
    long long integer(const std::string& key, long long min, long long max, long long fallback);
    bool boolean(const std::string& key, bool fallback);
    std::string string(const std::string& key);
    std::string string(const std::string& key, const std::string& fallback);
    /// One of `allowed`.
    std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                       const std::string& fallback);
    /// An array of three finite numbers.
    Eigen::Vector3d vec3(const std::string& key);
    Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback);
    /// A nested object, to be read with its own JsonFields; marks the key as used.
    const nlohmann::json& object(const std::string& key);
    /// A nested array; marks the key as used.
    const nlohmann::json& array(const std::string& key);

    /// Throws InputError naming the first key that was never read.
    void reject_unknown_keys() const;

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

private:
    const nlohmann::json& get(const std::string& key);
    const nlohmann::json& object_;
    std::string file_;
    std::string path_;
    std::set<std::string> used_;
};

}  // namespace ladarsim
