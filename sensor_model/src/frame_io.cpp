#include "ladarsim/sensor_model/frame_io.h"

#include <cstdio>

namespace ladarsim::sensor_model {

std::string frame_file_stem(std::uint64_t index) {
    char stem[24];
    std::snprintf(stem, sizeof stem, "%06llu", static_cast<unsigned long long>(index));
    return stem;
}

}  // namespace ladarsim::sensor_model
