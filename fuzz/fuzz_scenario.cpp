// Any bytes as a scenario file: load_scenario may refuse them (InputError), never crash.
#include "input_file.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/sensor_model/render/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        ladarsim::sensor_model::load_scenario(ladarsim::fuzz::write_input(data, size, "scenario.json"));
    } catch (const ladarsim::InputError&) {
    }
    return 0;
}
