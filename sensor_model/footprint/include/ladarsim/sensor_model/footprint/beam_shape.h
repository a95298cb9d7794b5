#pragma once
// A beam's footprint in the coordinates its sub-rays are placed in: offsets from its axis, round in
// units of the azimuth divergence (an elliptical beam stretches them in elevation).
#include <cmath>
#include <utility>

#include <Eigen/Core>

#include "ladarsim/sensor_model/footprint/footprint.h"

namespace ladarsim::sensor_model {

class BeamShape {
public:
    /// `ellipticity`: the beam's elevation divergence over its azimuth divergence.
    BeamShape(Footprint footprint, double ellipticity) : footprint_(std::move(footprint)), ellipticity_(ellipticity) {}

    const Footprint& footprint() const { return footprint_; }
    double ellipticity() const { return ellipticity_; }
    /// Footprint coordinates of a direction given in beam coordinates (x along the beam).
    Eigen::Vector2d offset_of(const Eigen::Vector3d& in_beam) const {
        return {std::atan2(in_beam.y(), in_beam.x()), std::atan2(in_beam.z(), in_beam.x()) / ellipticity_};
    }
    /// Beam coordinates of a footprint offset.
    Eigen::Vector3d in_beam(double x_rad, double y_rad) const;
    /// The beam's irradiance at a footprint offset, relative to its axis.
    double irradiance(double x_rad, double y_rad) const {
        const double w = footprint_.waist_rad();
        return std::exp(-2.0 * (x_rad * x_rad + y_rad * y_rad) / (w * w));
    }

private:
    Footprint footprint_;
    double ellipticity_;
};

}  // namespace ladarsim::sensor_model
