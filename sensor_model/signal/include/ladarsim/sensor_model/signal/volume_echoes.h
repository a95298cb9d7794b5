#pragma once
// Fog and cloud along a sub-ray: the attenuation of what lies behind, and the backscatter from
// inside, placed by free-path sampling.
#include <span>
#include <vector>

#include "ladarsim/raytrace/hit.h"
#include "ladarsim/sensor_model/signal/beam_receiver.h"
#include "ladarsim/sensor_model/signal/counter_random.h"

namespace ladarsim::sensor_model {

/// Optical depth of the volume media a ray crosses between 0 and `range_m`.
double optical_depth(std::span<const raytrace::VolumeSegment> segments, double range_m);

/// Adds one backscatter echo per volume segment crossed before `surface_range_m` (and past the
/// receiver's minimum range, where its depths are taken from) to `volumes`
/// (one BeamSurface per volume object, created on first use). For a segment of depth d entered at
/// R0, the expected energy from depth s is E_sub T(R)^2 exp(-2 tau_0) beta exp(-2 alpha s) A_r / R^2 ds;
/// drawing s from alpha exp(-alpha s) / (1 - exp(-alpha d)) (the free path to the first
/// scattering, truncated to the segment) and weighting by the ratio gives the unbiased echo
///   E = E_sub T(R)^2 exp(-2 tau_0) (beta / alpha) (1 - exp(-alpha d)) exp(-alpha s) A_r / R^2,
/// with E_sub the sub-ray's pulse energy after the optics, T the clear-air transmission and tau_0
/// the optical depth before the segment. Each segment takes `free_paths` such depths, stratified
/// (one uniform draw places one in each n-th of the scattering probability; they cost no ray), and
/// adds their mean as one echo at their energy-weighted mean range, stretched by their spread.
void add_volume_echoes(std::span<const raytrace::VolumeSegment> segments, double surface_range_m,
                       double subray_energy_j, double sub_ray_weight, double aperture_area_m2,
                       const BeamReceiver& receiver, RandomSequence& draws, std::vector<BeamSurface>& volumes,
                       int free_paths = 1);

}  // namespace ladarsim::sensor_model
