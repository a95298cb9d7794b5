#pragma once
// Geometry that cannot be what the user meant, found from the scenario before anything is rendered.
#include <string>
#include <vector>

#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::sensor_model {

/// One message per finding over frames 0..frames-1 (each naming the first frame it concerns and
/// how many), in this order:
/// - the sensor inside an object: beams (their axes at the first, middle and last frame's
///   pointing) meeting a surface closer than the receiver's min_range_m (0.1 m without one);
/// - a cue the gimbal cannot reach (beyond az_limit_deg or the elevation limits): the gimbal parks
///   at its limit (not checked for a fixed head, whose limits are all 0);
/// - an object of interest (the cue object, or every drone when there is no cue) farther than the
///   receiver's max_range_m: it returns nothing.
/// `renderer` gives the frames' times and pointings and traces the beams' axes.
std::vector<std::string> geometry_warnings(const Scenario& scenario, FrameRenderer& renderer, int frames);

}  // namespace ladarsim::sensor_model
