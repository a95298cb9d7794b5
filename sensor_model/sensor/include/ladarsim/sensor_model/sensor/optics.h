#pragma once
// The receiving telescope and filter: how much of the echo and of the sunlit scene reach the detector.
#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

/// The paper gives no aperture or optics; the paper LADAR's values are estimates for a 1560 nm
/// InGaAs APD receiver, in the sensor file so a scenario can override them.
struct Optics {
    double aperture_diameter_m = 0.0;
    double optics_efficiency = 0.0;   ///< transmit x receive optics and filter transmission
    double receiver_fov_mrad = 0.0;   ///< full angle seen by the detector (for solar background)
    double filter_width_nm = 0.0;     ///< optical band-pass around the wavelength

    double aperture_area_m2() const;

    static Optics read(JsonFields& optics);
    nlohmann::json to_json() const;
};

}  // namespace ladarsim::sensor_model
