#pragma once
// Oriented discs (a recorded map's) seen along a line of directions (1, X, t) in a beam's
// coordinates (x along the beam, y left, z up), t the tangent of the elevation offset: each disc
// the line's plane cuts is a chord, and what a ray sees is the nearest chord at its t (the ray
// tracer's nearest-disc rule).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace ladarsim::sensor_model {

/// One disc's chord on one line: its offsets t = tan(elevation offset) from t_lo to t_hi, and
/// the reciprocal of the distance along the line's direction (1, X, t) to its plane,
/// g0 + g1 t (linear in t: the nearest surface is the largest).
struct DiscChord {
    double t_lo, t_hi, g0, g1;
    std::uint32_t disc;
};
/// A visible piece of a line: [t_lo, t_hi] of `disc`'s chord (or a gap: disc = kGapPiece).
struct VisiblePiece {
    double t_lo, t_hi;
    std::uint32_t disc;
    double g0, g1;
};
inline constexpr std::uint32_t kGapPiece = 0xFFFFFFFFu;

/// The chord of a disc (centre p, unit normal n, radius r; beam coordinates) on the line of
/// directions (1, X, t), clipped to t_min <= t <= t_max; false where the line's plane misses it.
bool disc_chord(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double r, double X, double t_min, double t_max, DiscChord& out);
/// The same clipped to |t| <= t_max (a beam's own lines, centred on its axis).
inline bool disc_chord(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double r, double X, double t_max, DiscChord& out) {
    return disc_chord(p, n, r, X, -t_max, t_max, out);
}
/// The nearest of `chords` along [t0, t1], gaps included, in order, appended to `out`.
void lower_envelope(std::vector<DiscChord>& chords, double t0, double t1, std::vector<VisiblePiece>& out);

}  // namespace ladarsim::sensor_model
