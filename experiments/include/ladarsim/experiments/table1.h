#pragma once
// The paper's Table 1, an experiment on the sensor model: how many returns a small target gives, by
// the paper's analytic Eqs. 4-8 and rendered by ray tracing the beam pattern with the received-signal
// model (`ladarsim table1`, docs/table1.md).
#include <cstdint>
#include <functional>
#include <string>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/scene/mesh.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::experiments {

/// One row of the paper's Table 1 as its Eqs. 4-8 give it.
struct AnalyticPointCount {
    double fov_m;      ///< Eq. 4: 2 tan(FOV / 2) R
    int lines_az;      ///< Eq. 5: ROUNDUP(T / (FOV_m / SR_AZ))
    int lines_el;
    double tbi_az_m;   ///< Eq. 7: (T / 2 + BI R) x 2
    double tbi_el_m;
    double tp;         ///< Eq. 8: ROUNDUP(TBI_AZ SR_AZ / FOV_m x TBI_EL SR_EL / FOV_m)
};

/// The paper's Eqs. 4-8 for a target of `target_m` at `range_m` seen by `beams_az` x `beams_el`
/// beams over a square field of `fov_deg`, divergence `divergence_mrad`. Eq. 6, the beam-
/// intersection angle, is read as BI = (B SR - FOV) / (SR - 1) (degrees): with a 0.65 deg field and
/// T / 2 inside Eq. 7 this reproduces every printed FOV_m, BL and TBI of Table 1; as printed,
/// (B SR) - FOV (SR - 1) is negative.
AnalyticPointCount paper_point_count(double range_m, double fov_deg, double target_m, int beams_az, int beams_el,
                                     double divergence_mrad);

/// Table 1 as printed (range, FOV_m, BL_AZ, BL_EL, TBI_AZ, TBI_EL, TP).
struct PrintedTable1Row {
    double range_m, fov_m;
    int lines_az, lines_el;
    double tbi_az_m, tbi_el_m;
    int tp;
};
const std::vector<PrintedTable1Row>& printed_table1();

/// Returns on a target over many frames.
struct CountStatistics {
    double mean = 0.0, stddev = 0.0;
    int min = 0, max = 0;
    std::vector<int> per_frame;
};

/// Returns the detector reports on a lone target (no background, clear air) at `range_m`, its
/// centre `az_rad` / `el_rad` off the field centre, facing the sensor; `frame` keys the noise.
/// `footprint_samples` as in RenderSettings (0: adaptive footprints).
int rendered_point_count_at(const sensor_model::Sensor& sensor, int footprint_samples, std::shared_ptr<const scene::Model> target,
                            double range_m, double az_rad, double el_rad, bool noise, std::uint64_t seed,
                            std::uint64_t frame);

/// Renders `frames` frames of a lone target (no background, clear air) centred in the sensor's
/// field at `range_m`, facing the sensor, moved by a random sub-beam offset (uniform over one
/// beam pitch in azimuth and elevation) in each frame; counts the returns the detector reports
/// on it. Deterministic for a seed. `frame_done` is called after each frame.
CountStatistics rendered_point_count(const sensor_model::Sensor& sensor, int footprint_samples, std::shared_ptr<const scene::Model> target,
                                     double range_m, int frames, bool noise, std::uint64_t seed,
                                     const std::function<void()>& frame_done = {});

/// Table 1 side by side: for each printed range, the paper's row, Eqs. 4-8 under the stated 0.5 deg
/// field and the 0.65 deg reading, and the rendered counts (mean, stddev, min, max) for the plate
/// and the drone with noise on and off. `progress` is called with (frames rendered, frames in all)
/// once before the first frame and after each frame.
nlohmann::json table1_comparison(const sensor_model::Sensor& sensor, int footprint_samples, std::shared_ptr<const scene::Model> plate,
                                 std::shared_ptr<const scene::Model> drone, int frames, std::uint64_t seed,
                                 const std::function<void(int done, int total)>& progress = {});

/// The comparison as a markdown table a person reads at a glance.
std::string table1_markdown(const nlohmann::json& rows);

}  // namespace ladarsim::experiments
