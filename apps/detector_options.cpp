#include "detector_options.h"

#include <limits>

#include "option_checks.h"

namespace ladarsim::apps {

void DetectorOptions::add(CLI::App& command) {
    command.add_option("--method", method_name, "rbnn | vrbnn | kalman")
        ->check(CLI::IsMember({"rbnn", "vrbnn", "kalman"}))
        ->capture_default_str();
    command.add_option("--radius", detector.rbnn_radius_m, "RBNN radius, m")->check(positive_number())->capture_default_str();
    command.add_option("--lambda", detector.lambda,
                       "V-RBNN lambda (default: a radius of 1.2 of the dataset sensor's coarser beam pitch per "
                       "metre, 180 for the paper's raster; Algorithm 1's own is 7)")
        ->check(positive_number());
    command.add_option("--bias", detector.bias_m, "V-RBNN bias, m (Algorithm 1: 0.01)")->check(positive_number(true))->capture_default_str();
    command.add_option("--resolution", detector.background_resolution_m, "Background octree voxel, m")
        ->check(positive_number())
        ->capture_default_str();
    command.add_option("--range-tolerance", detector.background_range_tolerance_m,
                       "Tracking every target, background subtraction also removes a point whose line of sight meets the "
                       "initial map within this distance, m (grazing footprints report ranges off their axis' hit)")
        ->check(positive_number(true))
        ->capture_default_str();
    command.add_option("--min-box", detector.min_box_m, "Smallest box extent per axis, m (0: the cluster's own)")
        ->check(positive_number(true))
        ->capture_default_str();
    command.add_option("--range-coherence", detector.range_coherence_m,
                       "Clutter from clouds and fog: a small hard target's returns agree in range within this, a volume's "
                       "backscatter does not (the cued tracker takes clusters' cores within twice this; every target's "
                       "tracker keeps clusters with 90 % of their returns within this of their median), m (0: off)")
        ->check(positive_number(true))
        ->capture_default_str();
    command.add_option("--target-size", target_size,
                       "The sensor-aware box's size where the returns cannot resolve it, m, along the sensor's x y z "
                       "(a small quadcopter's; scored beside the box around the points)")
        ->expected(3)
        ->check(positive_number())
        ->capture_default_str();
    command.add_option("--target", target_id, "Ground-truth id of the target to score (default: the first drone)")
        ->check(whole_number(1, std::numeric_limits<std::uint32_t>::max()));
}

detect::DetectorConfig DetectorOptions::config() const {
    detect::DetectorConfig c = detector;
    c.method = detect::method_from_string(method_name);
    c.target_size_m = {target_size[0], target_size[1], target_size[2]};
    return c;
}

std::optional<std::uint32_t> DetectorOptions::target() const {
    return target_id ? std::optional<std::uint32_t>(target_id) : std::nullopt;
}

}  // namespace ladarsim::apps
