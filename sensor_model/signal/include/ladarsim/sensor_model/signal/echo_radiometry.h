#pragma once
// What a sub-ray's echo brings to the detector, and how much it takes to be seen: the range
// equation and the receiver's threshold as the footprint integration asks them (docs/physics.md).
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/sensor_model/signal/beam_receiver.h"

namespace ladarsim::sensor_model {

class EchoRadiometry {
public:
    EchoRadiometry(const Sensor& sensor, const BeamReceiver& receiver) : sensor_(sensor), receiver_(receiver) {}

    /// Echo energy of a sub-ray carrying `weight` of the beam that meets a surface (fog: the two-way
    /// transmission of media on the way).
    double echo_energy_j(double weight, double reflectance, double cos_incidence, double range_m, double fog) const;
    /// Echo energy at which a pulse stretched by a range spread of `spread_m` peaks at the threshold.
    double threshold_energy_j(double spread_m) const;

    const Sensor& sensor() const { return sensor_; }
    const BeamReceiver& receiver() const { return receiver_; }

private:
    const Sensor& sensor_;
    const BeamReceiver& receiver_;
};

}  // namespace ladarsim::sensor_model
