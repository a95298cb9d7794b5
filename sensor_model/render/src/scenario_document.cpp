#include "scenario_document.h"

#include <optional>
#include <set>
#include <string>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim::sensor_model {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A path read relative to `from_dir`, rewritten to mean the same file when read relative to `to_dir`.
void rebase_path(json& value, const fs::path& from_dir, const fs::path& to_dir) {
    if (!value.is_string()) return;  // the scene reader reports the type
    const fs::path p = value.get<std::string>();
    if (p.is_absolute()) return;
    const fs::path target = fs::absolute(from_dir / p).lexically_normal();
    const fs::path relative = target.lexically_relative(fs::absolute(to_dir).lexically_normal());
    value = (relative.empty() ? target : relative).generic_string();
}

void rebase_paths(json& doc, const fs::path& from_dir, const fs::path& to_dir) {
    if (doc.contains("objects") && doc["objects"].is_array())
        for (json& o : doc["objects"])
            if (o.is_object() && o.contains("model")) rebase_path(o["model"], from_dir, to_dir);
    if (doc.contains("background") && doc["background"].is_object() && doc["background"].contains("file"))
        rebase_path(doc["background"]["file"], from_dir, to_dir);
    if (doc.contains("sensor") && doc["sensor"].is_object() && doc["sensor"].contains("file"))
        rebase_path(doc["sensor"]["file"], from_dir, to_dir);
}

std::optional<std::size_t> find_object(const json& objects, const json& change) {
    if (!change.is_object() || !change.contains("id")) return std::nullopt;
    for (std::size_t k = 0; k < objects.size(); ++k)
        if (objects[k].is_object() && objects[k].contains("id") && objects[k]["id"] == change["id"]) return k;
    return std::nullopt;
}

void apply_objects(json& base_objects, const json& changes, const std::string& name) {
    if (!changes.is_array()) throw InputError(name, "objects", "must be an array");
    for (std::size_t i = 0; i < changes.size(); ++i) {
        const json& change = changes[i];
        const std::string field = "objects[" + std::to_string(i) + "]";
        const std::optional<std::size_t> base = find_object(base_objects, change);
        if (change.is_object() && change.contains("remove")) {
            if (change["remove"] != true) throw InputError(name, field + ".remove", "must be true (or absent)");
            if (change.size() != 2 || !base)
                throw InputError(name, field + ".remove",
                                 "takes only the id of an object of the extended scenario");
            base_objects.erase(base_objects.begin() + static_cast<std::ptrdiff_t>(*base));
        } else if (base) {
            base_objects[*base].merge_patch(change);
        } else {
            base_objects.push_back(change);
        }
    }
}

json read_document(const fs::path& file, std::set<fs::path>& chain);

// `doc` as read from `file` (which names it in errors and whose folder its relative paths start
// from), with its `extends` chain applied.
json extend_document(json doc, const fs::path& file, std::set<fs::path>& chain) {
    if (!doc.is_object() || !doc.contains("extends")) return doc;
    const std::string name = file.string();
    if (!doc["extends"].is_string()) throw InputError(name, "extends", "must be the path of a scenario file");
    const fs::path base_file = file.parent_path() / doc["extends"].get<std::string>();
    if (!fs::is_regular_file(base_file)) throw InputError(name, "extends", "no such file: " + base_file.string());
    if (!chain.insert(fs::weakly_canonical(base_file)).second)
        throw InputError(name, "extends", "extends itself through " + base_file.string());

    json base = read_document(base_file, chain);
    if (!base.is_object()) throw InputError(base_file.string(), "(file)", "must hold a JSON object");
    // Absolute: a file named without a folder ("variant.json") has an empty parent path.
    rebase_paths(base, fs::absolute(base_file).parent_path(), fs::absolute(file).parent_path());
    doc.erase("extends");
    for (auto& [key, value] : doc.items()) {
        if (key == "objects") {
            if (!base.contains("objects")) base["objects"] = json::array();
            if (!base["objects"].is_array()) throw InputError(base_file.string(), "objects", "must be an array");
            apply_objects(base["objects"], value, name);
        } else {
            json patch = json::object();
            patch[key] = value;
            base.merge_patch(patch);
        }
    }
    return base;
}

json read_document(const fs::path& file, std::set<fs::path>& chain) { return extend_document(read_json(file), file, chain); }

}  // namespace

json read_scenario_document(const fs::path& file) {
    std::set<fs::path> chain;
    if (fs::exists(file)) chain.insert(fs::weakly_canonical(file));
    return read_document(file, chain);
}

json extend_scenario_document(json document, const fs::path& file) {
    std::set<fs::path> chain;
    return extend_document(std::move(document), file, chain);
}

}  // namespace ladarsim::sensor_model
