// Any bytes as a PCD frame: read_frame_pcd may refuse them (InputError), never crash.
#include "input_file.h"
#include "ladarsim/scene/input_error.h"
#include "ladarsim/sensor_model/pcd_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        ladarsim::sensor_model::read_frame_pcd(ladarsim::fuzz::write_input(data, size, "frame.pcd"));
    } catch (const ladarsim::InputError&) {
    }
    return 0;
}
