#include "ladarsim/sensor_model/galvo_raster.h"

#include <numbers>

namespace ladarsim::sensor_model {

GalvoRaster::GalvoRaster(const SensorConfig& config)
    : columns_(config.beams_az),
      rows_(config.beams_el),
      field_az_rad_(config.field_az_deg * std::numbers::pi / 180.0),
      field_el_rad_(config.field_el_deg * std::numbers::pi / 180.0),
      line_duration_s_(config.line_duration_s()),
      sweep_(config.sweep),
      scan_(config.scan) {}

RasterBeam GalvoRaster::beam(int row, int step) const {
    RasterBeam b;
    b.row = row;
    const bool reversed = scan_ == ScanPattern::galvo && sweep_ == GalvoSweep::triangle && b.row % 2 == 1;
    b.column = reversed ? columns_ - 1 - step : step;
    b.az_offset_rad = (0.5 - (b.column + 0.5) / columns_) * field_az_rad_;
    b.el_offset_rad = (0.5 - (b.row + 0.5) / rows_) * field_el_rad_;
    b.time_offset_s = scan_ == ScanPattern::galvo
                          ? line_duration_s_ * (b.row + static_cast<double>(step) / columns_)
                          : line_duration_s_ * (step + static_cast<double>(row) / rows_) / columns_;
    return b;
}

}  // namespace ladarsim::sensor_model
