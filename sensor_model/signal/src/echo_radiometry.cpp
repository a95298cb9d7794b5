#include "ladarsim/sensor_model/signal/echo_radiometry.h"

#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/sensor_model/signal/range_equation.h"

namespace ladarsim::sensor_model {

double EchoRadiometry::echo_energy_j(double weight, double reflectance, double cos_incidence, double range_m, double fog) const {
    const double t = receiver_.transmission(range_m);
    return lambertian_echo_energy_j(sensor_.transmitter.pulse_energy_j(), weight, sensor_.optics.optics_efficiency, t * t * fog,
                                    reflectance, cos_incidence, sensor_.optics.aperture_area_m2(), range_m);
}

double EchoRadiometry::threshold_energy_j(double spread_m) const {
    const PulseShape shape = PulseShape::of(sensor_.transmitter.pulse_width_ns * 1e-9, 2.0 * spread_m / kSpeedOfLight_mps);
    const ApdReceiver& apd = receiver_.apd();
    return apd.threshold_a() / (apd.amps_per_watt() * shape.peak_per_joule());
}

}  // namespace ladarsim::sensor_model
