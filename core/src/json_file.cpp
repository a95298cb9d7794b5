#include "ladarsim/core/json_file.h"

#include <fstream>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {

void write_json(const std::filesystem::path& path, const nlohmann::json& value) {
    // Serialised before the file is created, so a value that cannot be written (invalid UTF-8)
    // leaves nothing behind.
    const std::string text = value.dump(2) + '\n';
    AtomicFile out(path);
    out.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
    out.commit();
}

nlohmann::json read_json(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path.string(), "(file)", "cannot open");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        // parse_error, and out_of_range for numbers beyond double (1e999): both unreadable text.
        throw InputError(path.string(), "(file)", std::string("not valid JSON: ") + e.what());
    }
}

}  // namespace ladarsim
