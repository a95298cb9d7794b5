// Any bytes, as a .glb and as a .gltf: load_gltf may refuse them (InputError), never crash.
#include "input_file.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    for (const char* name : {"input.glb", "input.gltf"}) {
        try {
            ladarsim::scene::load_gltf(ladarsim::fuzz::write_input(data, size, name));
        } catch (const ladarsim::InputError&) {
        }
    }
    return 0;
}
