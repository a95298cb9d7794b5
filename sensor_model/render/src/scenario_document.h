#pragma once
// A scenario file as one JSON document, after its `extends` chain is applied: a variant names the
// scenario it changes and holds only the changes, so the two cannot drift apart.
#include <filesystem>

#include <nlohmann/json.hpp>

namespace ladarsim::sensor_model {

/// Reads `file`; if it has "extends": "BASE.json" (relative to `file`), the base document (itself
/// possibly extending another) is read and `file`'s keys applied to it:
/// - `objects`: entries are matched by `id`; a matching entry is merged into the base's (RFC 7386
///   merge patch, so nested keys such as one trajectory field can be changed alone), an entry
///   {"id": N, "remove": true} drops object N, an entry with a new id is appended;
/// - every other key: RFC 7386 merge patch (objects merge key by key, `null` deletes a key, arrays
///   and values replace).
/// Relative paths of the base (`objects[].model`, `background.file`) are rewritten relative to
/// `file`, so a variant may live in another folder. Throws InputError naming the file and field
/// for an unreadable base, a cycle, a non-string `extends`, or a removal of an id the base lacks.
nlohmann::json read_scenario_document(const std::filesystem::path& file);

/// The same for a document already in memory: `file` is the name it goes by, never read: errors
/// name it, and its folder is where `extends` and relative paths start from.
nlohmann::json extend_scenario_document(nlohmann::json document, const std::filesystem::path& file);

}  // namespace ladarsim::sensor_model
