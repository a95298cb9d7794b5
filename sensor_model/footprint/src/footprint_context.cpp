#include "footprint_context.h"

#include <algorithm>
#include <cmath>

#include "ladarsim/core/units.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/sensor_model/signal/range_equation.h"

namespace ladarsim::sensor_model {

namespace {

/// A target's outline takes at most 1 / tolerance^2 of these (as a sampled estimate's error falls
/// with its samples), between 256 (tolerance 0.05 and above) and 1024 (0.025 and below); so does
/// a footprint over a recorded map, in stratified cells. A small
/// target of many surfaces within one return (a quadcopter's arms, rotors and body) keeps the
/// estimate's variance above a coarse tolerance through its inner edges: with one cap for every
/// tolerance, each beam near a drone ran to 1024 whatever the tolerance asked.
constexpr double kOutlineSamplesPerInverseTolerance2 = 0.64;
constexpr std::size_t kOutlineSamplesMin = 256, kOutlineSamplesMax = 1024;
/// Objects subtending less than this many footprint radii can hide between the probes or cover a
/// part of a footprint no probe sees: they are tested against each beam's cone and sampled.
constexpr double kSmallObjectFootprints = 8.0;

}  // namespace

FootprintContext::FootprintContext(const FootprintSettings& s, const Sensor& sensor_parts, const raytrace::TracedScene& scene,
                                   const EchoRadiometry& echoes)
    : settings(s),
      sensor(sensor_parts),
      traced(scene),
      radiometry(echoes),
      adaptive(s.samples == 0),
      max_range_m(sensor_parts.receiver.max_range_m),
      return_gap_m(sensor_parts.receiver.return_gap_m),
      outline_samples(std::clamp(static_cast<std::size_t>(kOutlineSamplesPerInverseTolerance2 / (s.tolerance * s.tolerance)),
                                 kOutlineSamplesMin, kOutlineSamplesMax)),
      shape(Footprint(sensor_parts.transmitter.divergence_mrad * kMrad, adaptive ? kPlaneQuadrature : s.samples, s.truncation),
            sensor_parts.transmitter.divergence_el_mrad / sensor_parts.transmitter.divergence_mrad),
      small_object_rad(kSmallObjectFootprints * shape.footprint().max_offset_rad()),
      pulse_sigma_m(PulseShape::of(sensor_parts.transmitter.pulse_width_ns * 1e-9).sigma_s * 0.5 * kSpeedOfLight_mps),
      threshold_j(echoes.threshold_energy_j(0.0)),
      grid_base(static_cast<int>(std::sqrt(static_cast<double>(outline_samples)))),
      aperture_radius2(aperture_radius2_m2(sensor_parts.optics.aperture_area_m2())) {}

}  // namespace ladarsim::sensor_model
