#pragma once
// A recorded map's visibility shared by the beams of a raster row (docs/sensor.md, "Footprint and
// returns"). The map is static and the gimbal holds still through a frame, and a row's beams share
// their elevation and overlap along it (the paper's raster: about 16 footprints side by side). So
// the lines across footprints are planes through the gimbal's vertical axis, the same for every
// beam of the row: the nearest disc chords along each (and what the static scene shows through
// their gaps) are found once a frame, and each beam only weighs the pieces inside its footprint
// by its Gaussian. Targets in front of the map clip the pieces (FootprintPart::excluded), as they
// do for MapScanline, which this replaces where the raster allows it.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"
#include "ladarsim/sensor_model/sensor/scan_pattern.h"
#include "map_discs.h"

namespace ladarsim::sensor_model {

class MapRows final : public FootprintStrategy {
public:
    /// Whether `raster`'s rows keep one elevation each and their footprints overlap along them.
    static bool applicable(const ScanPattern& raster, const BeamShape& shape);
    /// `lines_per_pitch` lines for each step between neighbouring beams of a row.
    MapRows(const FootprintContext& context, const MapDiscs& discs, const ScanPattern& raster, int lines_per_pitch);

    /// Visibility along `row`'s lines for a frame whose gimbal frame (x its boresight, z its vertical
    /// axis) is `world_from_gimbal`. Rows are independent: any thread may take any row.
    void start_row(int row, const Eigen::Matrix3d& world_from_gimbal);

    /// The echoes of the map over `part` (its rectangle: the square, or a cell of a target's
    /// outline) outside part.excluded, carrying part.share of the beam (its row started this
    /// frame). Empty where no line of the row crosses the rectangle; declined in media.
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;

private:
    /// A stretch of a line's visible surface, its range span within a fraction of the pulse's:
    /// a disc's, or what the static scene shows through a gap (object_id kGapPiece: nothing).
    struct Piece {
        double y_lo, y_hi;      ///< footprint elevation offsets (the same for every beam of the row)
        double cdf_lo, cdf_hi;  ///< the footprint axis' CDF there
        double range_m, spread_m, energy_per_weight;
        double g0, g1;          ///< a disc's: its reciprocal distance along (1, X, t), as DiscChord
        Eigen::Vector3d point_world;
        Eigen::Vector3f normal_world;
        std::uint32_t object_id;
        bool disc;
    };
    struct Line {
        double azimuth_rad;  ///< in the gimbal frame
        double X, s;         ///< tan(azimuth - the row frame's) and sqrt(1 + X^2)
        std::uint32_t first_piece;
    };
    struct Row {
        double elevation_rad = 0.0;
        double first_azimuth_rad = 0.0;   ///< line 0's
        double middle_azimuth_rad = 0.0;  ///< the row frame's x, in the gimbal frame
        Eigen::Matrix3d world_from_row;  ///< the gimbal frame turned to the row's middle azimuth
        std::vector<Line> lines;         ///< by increasing azimuth, a last one closing the pieces
        std::vector<Piece> pieces;
        /// Each piece's y_hi apart: a beam's search along a line touches a cache line per step of
        /// it instead of per piece.
        std::vector<double> piece_y_hi;
    };

    /// The offsets along `line` of `row` of elevation offset y (footprint units): t of (1, X, t).
    double t_of(const Row& row, const Line& line, double y) const;
    /// Splits a disc's visible piece of a line into pieces of short range span, appended to `out`.
    void add_disc_piece(const Row& row, const Line& line, double ta, double tb, std::uint32_t disc, double g0, double g1,
                        std::vector<Piece>& out) const;

    const FootprintContext& context_;
    const MapDiscs& discs_;
    double line_pitch_rad_;  ///< between lines, in azimuth
    int columns_;
    std::vector<double> azimuth_of_cell_;  ///< each raster cell's azimuth offset (cell = row * columns + step)
    std::vector<Row> rows_;
};

}  // namespace ladarsim::sensor_model
