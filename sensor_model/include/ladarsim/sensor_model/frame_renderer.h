#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/beam_receiver.h"
#include "ladarsim/sensor_model/footprint.h"
#include "ladarsim/sensor_model/frame.h"
#include "ladarsim/sensor_model/galvo_raster.h"
#include "ladarsim/sensor_model/gimbal.h"
#include "ladarsim/sensor_model/scenario.h"

namespace ladarsim::sensor_model {

/// Turns a scenario into frames: fires every beam of the raster at its own time, traces its
/// footprint's sub-rays, gives each sub-ray its echo energy by the range equation, gathers the
/// echoes into the distinct surfaces along the beam and hands them to the BeamReceiver, which
/// reports what the detector sees (docs/physics.md).
///
/// Frames are independent given the scenario and seed (the gimbal's pointing is replayed from
/// frame 0), and beams are traced in parallel with results that do not depend on thread count.
class FrameRenderer {
public:
    explicit FrameRenderer(const Scenario& scenario);

    Frame render(std::uint64_t index);
    /// Frame `index` with the gimbal held at `pointing` instead of where the cue takes it.
    Frame render_at(std::uint64_t index, GimbalPointing pointing);

    double frame_start_s(std::uint64_t index) const;
    GimbalPointing gimbal_pointing(std::uint64_t index);
    const GalvoRaster& raster() const { return raster_; }

private:
    /// All returns of one raster line, in column order.
    std::vector<Return> trace_row(int row, GimbalPointing pointing, double frame_start_s, std::uint64_t frame) const;
    std::vector<GroundTruthObject> ground_truth(double time_s, const std::vector<Return>& returns) const;
    GimbalPointing cue_pointing(double time_s) const;

    const Scenario& scenario_;
    raytrace::TracedScene traced_;
    GalvoRaster raster_;
    Footprint footprint_;
    BeamReceiver receiver_;
    std::vector<GimbalPointing> pointing_by_frame_;
};

/// Centre of an object's model bounds in the world at `time_s`.
Eigen::Vector3d object_centre_world(const scene::SceneObject& object, double time_s);

}  // namespace ladarsim::sensor_model
