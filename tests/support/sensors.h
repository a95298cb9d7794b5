#pragma once
// The bundled sensors as tests use them, and the one change tests make to them: another raster.
#include <memory>

#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "ladarsim/sensor_model/render/scenario.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::test {

/// Sub-rays lie within this many 1/e^2 radii unless a scenario says otherwise.
inline const double kTruncation = sensor_model::RenderSettings{}.footprint_truncation;

inline sensor_model::Sensor paper_sensor() { return sensor_model::sensor_preset("paper_ladar"); }

/// The paper LADAR's galvo raster parameters.
inline sensor_model::GalvoRaster::Parameters paper_raster() {
    return dynamic_cast<const sensor_model::GalvoRaster&>(*paper_sensor().scan).parameters();
}

/// `sensor` scanning `beams_az` x `beams_el` beams over `field_az_deg` x `field_el_deg` with the
/// paper's galvo timing.
inline void set_raster(sensor_model::Sensor& sensor, int beams_az, int beams_el, double field_az_deg, double field_el_deg) {
    sensor_model::GalvoRaster::Parameters p = paper_raster();
    p.beams_az = beams_az;
    p.beams_el = beams_el;
    p.field_az_deg = field_az_deg;
    p.field_el_deg = field_el_deg;
    sensor.scan = std::make_shared<sensor_model::GalvoRaster>(p);
}

}  // namespace ladarsim::test
