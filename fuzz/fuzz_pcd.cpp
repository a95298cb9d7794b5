// Any bytes as a PCD frame: read_frame_pcd may refuse them (InputError), never crash.
#include "input_file.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/core/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        ladarsim::read_frame_pcd(ladarsim::fuzz::write_input(data, size, "frame.pcd"));
    } catch (const ladarsim::InputError&) {
    }
    return 0;
}
