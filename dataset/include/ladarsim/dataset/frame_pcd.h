#pragma once
// Frames as PCD point clouds: one point per return, its fields named after the Return's.
#include <filesystem>
#include <vector>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/pcd_file.h"

namespace ladarsim {

/// The returns as the cloud write_frame_pcd writes: one point per return, the fields below.
PcdCloud frame_pcd_cloud(const std::vector<Return>& returns);

/// Writes the frame's returns as a binary PCD, one point per return, packed (56 bytes a point):
///   x y z intensity (F4), range_m time_s (F8), beam_az beam_el (F4, rad), column row (U2),
///   return_index (U1), object_id (U4), snr (F4), source pulse_offset saturated (U1);
/// WIDTH = returns, HEIGHT = 1, VIEWPOINT at the sensor origin. Atomic (see AtomicFile).
void write_frame_pcd(const std::filesystem::path& path, const Frame& frame);

/// Reads a PCD written by write_frame_pcd, or a recorded cloud (any PCD read_pcd reads) with at
/// least x y z: fields it lacks stay 0, fields it has that a Return lacks are skipped. Points
/// whose x, y or z is NaN are skipped: PCL marks beams without a return that way in organised
/// clouds. Throws InputError naming the file and the header keyword (or DATA) for what read_pcd
/// rejects, a Return field with COUNT other than 1, or a value that does not fit its Return field.
std::vector<Return> read_frame_pcd(const std::filesystem::path& path);

}  // namespace ladarsim
