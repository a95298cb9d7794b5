#pragma once
// Frames as OpenEXR range images: one pixel per beam of the raster, so a frame can be looked at
// in any image viewer and compared pixel by pixel.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// object_id of a pixel whose beam has no return (0 is the background map).
inline constexpr std::uint32_t kNoReturnObjectId = 0xFFFFFFFEu;

/// The first return of every beam, row-major: pixel (column, row) is at row * columns + column,
/// row 0 the top line of the raster.
struct RangeImage {
    int columns = 0;
    int rows = 0;
    std::vector<float> range_m;           ///< 0 where the beam has no return
    std::vector<float> intensity;         ///< 0 where the beam has no return
    std::vector<std::uint32_t> object_id; ///< kNoReturnObjectId where the beam has no return
    std::vector<float> strongest_range_m;   ///< of the beam's strongest (most intense) return; 0 where none
    std::vector<float> strongest_intensity; ///< of the beam's strongest return; 0 where none
    std::uint64_t frame_index = 0;
    double start_time_s = 0.0;
    double end_time_s = 0.0;

    std::size_t pixel(int column, int row) const {
        return static_cast<std::size_t>(row) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(column);
    }
};

/// The image write_frame_exr writes of a frame: the first return (return_index 0) of each beam,
/// and its strongest (most intense) return.
/// Throws std::invalid_argument if the frame has no raster or a return lies outside it.
RangeImage range_image_of(const Frame& frame);

/// One channel of the EXR: its name, and its plane of a RangeImage (FLOAT or UINT).
struct RangeImageChannel {
    const char* name;
    const std::vector<float>* float_plane = nullptr;
    const std::vector<std::uint32_t>* uint_plane = nullptr;
};

/// The channels write_frame_exr writes, in its order: Y (the range again, for ordinary viewers),
/// range_m, intensity, object_id, strongest_range_m, strongest_intensity.
std::vector<RangeImageChannel> range_image_channels(const RangeImage& image);

/// Writes a columns x rows EXR (ZIP), one pixel a beam: FLOAT `range_m` and `intensity` and UINT
/// `object_id` of its first (nearest) return (return_index 0), FLOAT `strongest_range_m` and
/// `strongest_intensity` of its most intense return (the same as the first when it has one), and
/// FLOAT `Y` = range_m so that ordinary viewers show a greyscale range image. No-return pixels are
/// 0 rather than NaN, which many viewers mishandle, with object_id kNoReturnObjectId (4294967294),
/// unlike a false alarm's kNoObject (4294967295). Attributes: `frame_index` (int), `start_time_s`,
/// `end_time_s` (double).
/// Throws std::invalid_argument if the frame has no raster or a return lies outside it.
/// Atomic (see AtomicFile).
void write_frame_exr(const std::filesystem::path& path, const Frame& frame);

/// Reads an image written by write_frame_exr (the strongest channels are 0 in images written
/// before they existed); throws InputError naming the file and the
/// missing or mistyped channel or attribute, or OpenEXR's own complaint about the file.
RangeImage read_frame_exr(const std::filesystem::path& path);

}  // namespace ladarsim
