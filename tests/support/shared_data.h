#pragma once
// The shared data the tests read (recorded captures and maps, third-party models): ../shared/data
// beside the checkout, or under LADARSIM_SHARED_DIR from the environment, which runs the suite as
// a machine without the data does (point it at an empty directory: those tests report skipped).
#include <cstdlib>
#include <filesystem>

namespace ladarsim::test {

inline std::filesystem::path shared_data(const std::filesystem::path& relative) {
    const char* dir = std::getenv("LADARSIM_SHARED_DIR");
    return std::filesystem::path(dir && *dir ? dir : LADARSIM_SHARED_DIR) / "data" / relative;
}

}  // namespace ladarsim::test
