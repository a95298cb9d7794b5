#pragma once
// PLY point clouds (ASCII and binary, either byte order), a format recorded maps come in. Our own
// reader: PCL's pulled its I/O library and VTK into every ladarsim command, a tenth of a second of
// dynamic linking before each one started.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ladarsim::scene {

/// The scalar properties of a PLY file's `vertex` element, as doubles (exact for every PLY type).
struct PlyVertices {
    std::vector<std::string> properties;
    std::vector<double> values;  ///< vertex after vertex, each property in header order
    std::size_t count = 0;

    std::optional<std::size_t> property(std::string_view name) const;
    double value(std::size_t vertex, std::size_t property) const { return values[vertex * properties.size() + property]; }
};

/// Reads the vertex element; other elements (faces, before or after it) are skipped, list
/// properties of the vertex element too. Throws InputError naming the file and the header line or
/// element for anything malformed or cut short.
PlyVertices read_ply(const std::filesystem::path& file);

}  // namespace ladarsim::scene
