#pragma once
// How a recorded map's visible pieces along a line become echoes, the same for a footprint's own
// lines (MapScanline) and a raster row's shared ones (MapRows).

namespace ladarsim::sensor_model::map_pieces {

/// A piece whose range span exceeds this many pulse sigmas is cut into pieces that do not: the
/// receiver stretches each echo as a Gaussian of the piece's spread, which is a box's only while it
/// is narrow against the pulse.
inline constexpr double kSpanOverPulseSigma = 1.0;
/// At most this many cuts of one piece (a disc nearly edge-on to a line).
inline constexpr int kMaxCuts = 32;
/// Gaps carrying less of the beam than this are not worth a ray.
inline constexpr double kMinGapWeight = 1e-5;

}  // namespace ladarsim::sensor_model::map_pieces
