#include "exit_codes.h"

#include <cstdio>
#include <exception>

#include "ladarsim/dataset/input_error.h"
#include "ladarsim/sensor_model/render_dataset.h"

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
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}

}  // namespace ladarsim::apps
