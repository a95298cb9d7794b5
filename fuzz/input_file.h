#pragma once
// The fuzzers' bytes as a file with a given name, since the readers take paths.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace ladarsim::fuzz {

inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("ladarsim-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / name;
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}

}  // namespace ladarsim::fuzz
