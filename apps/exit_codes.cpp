#include "exit_codes.h"

#include <string>

#include <cstdio>
#include <exception>
#include <filesystem>

#include "ladarsim/core/input_error.h"
#include "ladarsim/sensor_model/render/render_dataset.h"

namespace ladarsim::apps {

int exit_code_of(const std::function<int()>& command, const MpiTeam* team) {
    try {
        return command();
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const sensor_model::FrameFailure& e) {
        if (team && team->size() > 1) std::fprintf(stderr, "error: process %d of %d: %s\n", team->rank(), team->size(), e.what());
        else std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    } catch (const std::filesystem::filesystem_error& e) {
        // The path and the system's reason, without the library's wording around them.
        std::fprintf(stderr, "error: %s: %s\n", e.path1().string().c_str(), e.code().message().c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}

int check_subcommand(const CLI::App& app, int argc, const char* const* argv) {
    const std::string first = argc > 1 ? argv[1] : "";
    if (!first.empty() && first[0] == '-') return 0;
    std::string valid;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (sub->check_name(first)) return 0;
        valid += (valid.empty() ? "" : ", ") + sub->get_name();
    }
    if (first.empty()) std::fprintf(stderr, "error: a subcommand is required: %s (ladarsim --help)\n", valid.c_str());
    else std::fprintf(stderr, "error: unknown subcommand '%s'; the subcommands are %s (ladarsim --help)\n", first.c_str(), valid.c_str());
    return 2;
}

}  // namespace ladarsim::apps
