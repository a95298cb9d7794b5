#pragma once
// The options that name and configure a detector, shared by `detect` (which writes its
// detections) and `benchmark` (which scores it as it runs).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "ladarsim/detect/tracker.h"

namespace ladarsim::apps {

struct DetectorOptions {
    std::string method_name = "vrbnn";
    detect::DetectorConfig detector;
    std::uint32_t target_id = 0;
    std::vector<double> target_size{0.3, 0.3, 0.06};

    /// Adds --method, --radius, --lambda, --bias, --resolution, --range-tolerance, --min-box,
    /// --target-size and --target to `command`, bound to these members.
    void add(CLI::App& command);
    /// The detector the parsed options describe.
    detect::DetectorConfig config() const;
    /// --target when given, else none (the first drone of the ground truth).
    std::optional<std::uint32_t> target() const;
};

}  // namespace ladarsim::apps
