#pragma once
// The initial map a detector subtracts, surveyed while a run's frames render.
#include <cstddef>
#include <exception>
#include <filesystem>

#include <tbb/task_group.h>

#include "ladarsim/sensor_model/render/scenario.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"

namespace ladarsim::sensor_model {

/// Where a run's frames looked: the survey needs the field the gimbal swept, not every pointing.
struct PointingExtent {
    int frames = 0;
    GimbalPointing first{};
    double az_lo = 0.0, az_hi = 0.0, el_lo = 0.0, el_hi = 0.0;
    bool one_pointing = true;

    void add(const GimbalPointing& p) {
        if (frames++ == 0) {
            first = p;
            az_lo = az_hi = p.az_rad;
            el_lo = el_hi = p.el_rad;
            return;
        }
        one_pointing = one_pointing && p.az_rad == first.az_rad && p.el_rad == first.el_rad;
        az_lo = std::min(az_lo, p.az_rad), az_hi = std::max(az_hi, p.az_rad);
        el_lo = std::min(el_lo, p.el_rad), el_hi = std::max(el_hi, p.el_rad);
    }
};

/// The initial map's survey, run while the frames render: it needs only where they will look (the
/// gimbal's replay), and run after them it kept the other cores waiting. Only the first process
/// of a team surveys. Writes `file` (see initial_map_survey.cpp for what the map holds).
class InitialMapSurvey {
public:
    InitialMapSurvey(const Scenario& scenario, const PointingExtent& looked, std::filesystem::path file);
    InitialMapSurvey(const InitialMapSurvey&) = delete;
    InitialMapSurvey& operator=(const InitialMapSurvey&) = delete;
    /// A run that stops before its end does not wait for its survey (millions of beams where the
    /// gimbal swept far): it is cancelled, and surveyed again by the run that finishes.
    ~InitialMapSurvey();
    /// Waits for the survey; returns the map's points, or throws what the survey threw.
    std::size_t points();

private:
    tbb::task_group surveying_;
    std::size_t points_ = 0;
    std::exception_ptr failure_;
};

}  // namespace ladarsim::sensor_model
