#pragma once
// The largest intensity of a dataset's frames: exports into formats with a fixed intensity range
// (KITTI's 0..1, LAS's 16 bits) divide by it, so that intensities keep their ratios across frames.
#include <filesystem>
#include <functional>
#include <vector>

namespace ladarsim {

/// The largest return intensity in the frame files `pcds` (0 when none is positive);
/// `frame_scanned(done, total)`, if set, is called after each file.
float largest_intensity(const std::vector<std::filesystem::path>& pcds,
                        const std::function<void(int done, int total)>& frame_scanned);

/// Progress of an export that scans the frames' intensities first, then writes each frame.
struct ExportProgress {
    std::function<void(int done, int total)> intensity_scanned;  ///< first pass, per frame read
    std::function<void(int done, int total)> frame_written;      ///< second pass, per frame written
};

}  // namespace ladarsim
