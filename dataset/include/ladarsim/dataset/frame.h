#pragma once
// The frame format: what the sensor reports for one raster scan. detect/ reads only this
// (from ladarsim's own renders or from recorded data), never how it was made.
//
// Sensor frame: fixed to the sensor mount (it does not turn with the gimbal), x forward,
// y left, z up, metres. Beam angles: azimuth positive towards +y (left), elevation positive up,
// both of the beam's centre direction in the sensor frame.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ladarsim {

/// What made a return (ground truth; a real sensor cannot tell).
enum class ReturnSource : std::uint8_t {
    surface = 0,      ///< a surface: object_id names it (0 = the background map)
    volume = 1,       ///< backscatter from inside fog or cloud: object_id names the volume
    false_alarm = 2,  ///< detector noise crossing the threshold: object_id is kNoObject
};

/// object_id of a return that no object made (false alarms).
inline constexpr std::uint32_t kNoObject = 0xFFFFFFFFu;

struct Return {
    Eigen::Vector3f position_sensor = Eigen::Vector3f::Zero();  ///< metres, sensor frame
    float intensity = 0.0f;        ///< detected energy in primary photo-electrons (noisy, clipped when saturated)
    double range_m = 0.0;          ///< from the sensor origin along the beam
    double time_s = 0.0;           ///< emission time of the pulse
    float beam_az_rad = 0.0f;
    float beam_el_rad = 0.0f;
    std::uint16_t column = 0;      ///< raster position, 0 = first azimuth beam
    std::uint16_t row = 0;         ///< raster position, 0 = top line
    std::uint8_t return_index = 0; ///< 0 = first (nearest) return of this beam
    std::uint32_t object_id = 0;   ///< 0 = background map; scenario objects have ids >= 1
    float snr = 0.0f;              ///< amplitude signal-to-noise ratio of the detected peak
    ReturnSource source = ReturnSource::surface;
    /// Ground truth of range folding: pulse periods between the pulse that made the return and
    /// the pulse whose range gate received it (the true range is range_m + this x c / (2 PRF)).
    std::uint8_t pulse_offset = 0;
    /// The detector's output clipped at its saturation current: `intensity` is the clip level, a
    /// lower bound of the echo (a real sensor knows this; its flag reports it).
    bool saturated = false;
};

/// Axis-aligned in the object's own frame, then placed by a pose: an oriented 3-D box.
struct OrientedBox {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< full extents along the box's own axes
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// Where one object really was during a frame.
struct GroundTruthObject {
    std::uint32_t object_id = 0;
    std::string object_class;
    std::string name;
    double time_s = 0.0;          ///< the pose is evaluated at the frame's mid-scan time
    OrientedBox box_world;
    OrientedBox box_sensor;
    std::uint32_t returns = 0;    ///< returns in the frame whose object_id is this object
    std::uint32_t folded_returns = 0;  ///< of those, reported at a folded (ambiguous) range
    std::uint32_t saturated_returns = 0;  ///< of those, clipped at the detector's saturation
};

struct Frame {
    std::uint64_t index = 0;
    double start_time_s = 0.0;
    double end_time_s = 0.0;
    int columns = 0;  ///< beams in azimuth
    int rows = 0;     ///< beams in elevation
    /// Sorted by (row, column, return_index).
    std::vector<Return> returns;
    std::vector<GroundTruthObject> ground_truth;
    /// Gimbal pointing (of the field centre) at the frame start, radians, sensor frame.
    double gimbal_az_rad = 0.0;
    double gimbal_el_rad = 0.0;
    /// The sensor's pose (world_from_sensor) at the frame's start, where it is known (a render;
    /// not a recording). On a moving platform each return's own pose is at its time_s
    /// (docs/scenario.md, "A moving platform").
    std::optional<Eigen::Isometry3d> sensor_pose;
};

}  // namespace ladarsim
