#include "ladarsim/dataset/frame_io.h"

#include <cstdio>

namespace ladarsim {

std::string frame_file_stem(std::uint64_t index) {
    char stem[24];
    std::snprintf(stem, sizeof stem, "%06llu", static_cast<unsigned long long>(index));
    return stem;
}

}  // namespace ladarsim
