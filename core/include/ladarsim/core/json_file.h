#pragma once
#include <filesystem>

#include <nlohmann/json.hpp>

namespace ladarsim {

/// Writes `value` pretty-printed (2-space indent, trailing newline), atomically (see AtomicFile).
void write_json(const std::filesystem::path& path, const nlohmann::json& value);

/// Parses a JSON file; throws InputError(file, "(file)", ...) if it cannot be opened or parsed.
nlohmann::json read_json(const std::filesystem::path& path);

}  // namespace ladarsim
