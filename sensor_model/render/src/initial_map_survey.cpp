#include "initial_map_survey.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "ladarsim/core/units.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"

namespace ladarsim::sensor_model {

namespace {

/// The initial map Algorithm 1 subtracts: a survey of the static world alone (the background map
/// and the objects that do not move, never a drone, bird or aircraft, nor a cloud or fog volume;
/// noise off) over every
/// direction the frames looked. When the gimbal moved, with beams at half the sensor's pitch over
/// the field it swept, so that a static surface's returns in any frame fall among the survey's
/// points; when every frame looked the same way (a fixed gimbal, a single frame), with the
/// sensor's own beams there: its frames fired in no other direction, and the survey costs one
/// frame's beams, not six. One centre sub-ray per beam: the map holds surfaces, not footprints.
/// Returns the number of points. The file is always written, with 0 points when the scene has
/// nothing static (or nothing static in view): one rule, so that its absence means a recorded
/// dataset.
std::size_t write_background_map(const Scenario& scenario, const PointingExtent& looked, const std::filesystem::path& file) {
    Scenario survey = scenario;
    // What does not move, but never a target: a drone, bird or aircraft hovering still is not part
    // of the map a detector subtracts (it would subtract the target itself). Nor a cloud or fog
    // volume: an initial map is surveyed on a clear day, and a medium's backscatter comes from
    // wherever its beams cross it, not from a surface; mapped, it would subtract whatever flies
    // inside it.
    std::erase_if(survey.scene.objects, [](const scene::SceneObject& o) {
        using scene::ObjectClass;
        const bool target = o.object_class == ObjectClass::drone || o.object_class == ObjectClass::bird ||
                            o.object_class == ObjectClass::plane;
        const bool medium = o.model && o.model->is_volume();
        return target || medium || !o.trajectory.is_static();
    });
    if ((survey.scene.objects.empty() && !survey.scene.background) || looked.frames == 0) {
        write_frame_pcd(file, Frame{});
        return 0;
    }
    survey.mount.cue_object_id = 0;
    survey.render.noise = false;
    survey.render.jitter = false;
    survey.render.footprint_samples = 1;
    survey.render.waveforms = false;  // the map is a survey's points, not a sensor's frame
    if (looked.one_pointing) {
        FrameRenderer renderer(survey);
        const Frame map = renderer.render_at(0, looked.first);
        write_frame_pcd(file, map);
        return map.returns.size();
    }
    const double az_lo = looked.az_lo, az_hi = looked.az_hi, el_lo = looked.el_lo, el_hi = looked.el_hi;
    const ScanPattern& scan = *scenario.sensor.scan;
    const double pitch_az = scan.field_az_deg() * kDeg / scan.columns(), pitch_el = scan.field_el_deg() * kDeg / scan.rows();
    // The field swept by the gimbal, plus a tenth of the field on each side.
    const double field_az = std::min(2.0 * std::numbers::pi, az_hi - az_lo + 1.2 * scan.field_az_deg() * kDeg);
    const double field_el = std::min(std::numbers::pi, el_hi - el_lo + 1.2 * scan.field_el_deg() * kDeg);
    // Half the sensor's pitch, coarsened if needed to stay within four million survey beams.
    const double coarsen = std::max(1.0, std::sqrt(field_az / (0.5 * pitch_az) * field_el / (0.5 * pitch_el) / 4e6));
    // Surveyed as by a galvo raster; a sensor without one is timed as a 1 kHz sawtooth (a static
    // scene's survey times carry no information).
    const auto* galvo = dynamic_cast<const GalvoRaster*>(&scan);
    GalvoRaster::Parameters raster;
    raster.field_az_deg = field_az / kDeg;
    raster.field_el_deg = field_el / kDeg;
    raster.beams_az = static_cast<int>(std::ceil(field_az / (0.5 * pitch_az * coarsen)));
    raster.beams_el = static_cast<int>(std::ceil(field_el / (0.5 * pitch_el * coarsen)));
    raster.galvo_rate_hz = galvo ? galvo->parameters().galvo_rate_hz : 1000.0;
    raster.sweep = galvo ? galvo->parameters().sweep : GalvoSweep::sawtooth;
    raster.frame_rate_hz = scan.frame_rate_hz();
    survey.sensor.scan = std::make_shared<GalvoRaster>(raster);
    FrameRenderer renderer(survey);
    Frame map = renderer.render_at(0, GimbalPointing{0.5 * (az_lo + az_hi), 0.5 * (el_lo + el_hi)});
    write_frame_pcd(file, map);
    return map.returns.size();
}

}  // namespace

InitialMapSurvey::InitialMapSurvey(const Scenario& scenario, const PointingExtent& looked, std::filesystem::path file) {
    surveying_.run([this, &scenario, looked, file = std::move(file)] {
        try {
            points_ = write_background_map(scenario, looked, file);
        } catch (...) {
            failure_ = std::current_exception();
        }
    });
}

InitialMapSurvey::~InitialMapSurvey() {
    surveying_.cancel();
    surveying_.wait();
}

std::size_t InitialMapSurvey::points() {
    surveying_.wait();
    if (failure_) std::rethrow_exception(failure_);
    return points_;
}

}  // namespace ladarsim::sensor_model
