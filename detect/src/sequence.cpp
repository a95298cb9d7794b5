#include "ladarsim/detect/sequence.h"

#include <cmath>
#include <map>
#include <tuple>
#include <string>

#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/dataset/manifest.h"
#include "ladarsim/detect/box_metrics.h"
#include "ladarsim/detect/clustering.h"
#include "ladarsim/detect/track_classification.h"

namespace ladarsim::detect {

namespace {

/// Frame i's intensities, empty for a sequence built without them.
const std::vector<float>& frame_intensity(const Sequence& s, std::size_t i) {
    static const std::vector<float> none;
    return i < s.intensity.size() ? s.intensity[i] : none;
}

}  // namespace

Sequence load_sequence(const std::filesystem::path& dir) {
    Sequence s;
    s.directory = dir;
    const std::vector<std::filesystem::path> files = frame_pcd_files(dir);
    const Manifest manifest = read_manifest(dir / "manifest.json");
    s.sensor = manifest.sensor;
    s.dataset_id = manifest.id;
    if (std::filesystem::exists(dir / "ground_truth.json")) s.truth = read_ground_truth_json(dir / "ground_truth.json");
    for (std::size_t i = 0; i < files.size(); ++i) {
        const std::vector<Return> returns = read_frame_pcd(files[i]);
        s.frames.push_back(positions_of(returns));
        s.intensity.push_back(intensities_of(returns));
        s.frame_index.push_back(i < s.truth.size() ? s.truth[i].index : i);
        // Without ground truth, frames are taken 1/20 s apart (the paper's frame rate).
        s.time_s.push_back(i < s.truth.size() ? 0.5 * (s.truth[i].start_time_s + s.truth[i].end_time_s) : i / 20.0);
    }
    s.boresight.assign(files.size(), std::nullopt);
    for (std::size_t i = 0; i < files.size() && i < manifest.pointing.size(); ++i) {
        if (!manifest.pointing[i]) continue;  // recorded frames carry no pointing
        const double az = manifest.pointing[i]->gimbal_az_rad, el = manifest.pointing[i]->gimbal_el_rad;
        s.boresight[i] = Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    }
    if (std::filesystem::exists(dir / "background.pcd")) s.background = positions_of(read_frame_pcd(dir / "background.pcd"));
    return s;
}

std::optional<std::uint32_t> default_target(const Sequence& s) {
    for (const auto& f : s.truth)
        for (const auto& o : f.objects)
            if (o.object_class == "drone") return o.object_id;
    return std::nullopt;
}

void check_target(const Sequence& s, std::uint32_t target, const std::filesystem::path& truth_file) {
    const std::string field = "--target " + std::to_string(target);
    if (s.truth.empty()) throw InputError(truth_file.string(), field, "no ground truth (a recorded dataset): nothing to score against");
    std::map<std::uint32_t, std::string> objects;
    for (const auto& f : s.truth)
        for (const auto& o : f.objects) objects.emplace(o.object_id, o.object_class);
    if (!objects.count(target)) {
        std::string known;
        for (const auto& [id, cls] : objects) {
            if (!known.empty()) known += ", ";
            known += std::to_string(id) + " (" + cls + ")";
        }
        throw InputError(truth_file.string(), field, "no object " + std::to_string(target) + " in the ground truth; its objects are " +
                                                         (known.empty() ? "none" : known));
    }
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
        if (truth_box(s, i, target)) continue;
        throw InputError(truth_file.string(), field,
                         "object " + std::to_string(target) + " (" + objects[target] + ") has no box in frame " + std::to_string(i) +
                             " of " + std::to_string(s.frames.size()) + " (" +
                             (i < s.truth.size() ? "not in the scene then" : "the ground truth has " + std::to_string(s.truth.size()) + " frames") +
                             "); scoring needs the target in every frame");
    }
}

std::optional<OrientedBox> truth_box(const Sequence& s, std::size_t i, std::uint32_t target) {
    if (i >= s.truth.size()) return std::nullopt;
    for (const auto& o : s.truth[i].objects) {
        if (o.object_id != target) continue;
        const auto& b = o.box_sensor;
        Eigen::AlignedBox3d box;
        for (int k = 0; k < 8; ++k) {
            const Eigen::Vector3d corner(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
            box.extend(b.centre + b.orientation * corner.cwiseProduct(b.size));
        }
        OrientedBox out;
        out.centre = box.center();
        out.size = box.sizes();
        return out;
    }
    return std::nullopt;
}

std::vector<Detection> detect_sequence(const Sequence& s, const DetectorConfig& config) {
    TargetTracker tracker(config, s.sensor, s.background);
    std::vector<Detection> out;
    for (std::size_t i = 0; i < s.frames.size(); ++i)
        out.push_back(tracker.process(s.frame_index[i], s.time_s[i], s.frames[i], s.boresight[i], frame_intensity(s, i)));
    return out;
}

double overlap(const Detection& d, ScoredBox box, Overlap kind, const OrientedBox& truth) {
    if (!d.found) return 0.0;
    const OrientedBox& scored = box == ScoredBox::points ? d.box : d.sensor_box;
    return kind == Overlap::volume ? axis_aligned_iou(scored, truth) : bev_iou(scored, truth);
}

namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
/// A box as detections files hold it: {"centre_m", "size_m"}.
nlohmann::json box_json(const OrientedBox& b) { return {{"centre_m", vector_json(b.centre)}, {"size_m", vector_json(b.size)}}; }

}  // namespace

const std::vector<std::tuple<std::string, ScoredBox, Overlap>>& scored_kinds() {
    static const std::vector<std::tuple<std::string, ScoredBox, Overlap>> kinds = {
        {"points_3d", ScoredBox::points, Overlap::volume},
        {"points_bev", ScoredBox::points, Overlap::bev},
        {"sensor_3d", ScoredBox::sensor_aware, Overlap::volume},
        {"sensor_bev", ScoredBox::sensor_aware, Overlap::bev}};
    return kinds;
}

SupervisedRuns supervised_runs(const Sequence& s, const DetectorConfig& config, std::uint32_t target) {
    SupervisedRuns runs;
    for (const auto& [name, box, kind] : scored_kinds()) runs[name] = supervised_run(s, config, target, box, kind);
    return runs;
}

std::vector<std::vector<TrackedObject>> track_sequence(const Sequence& s, const DetectorConfig& config) {
    MultiTargetTracker tracker(config, s.sensor, s.background);
    std::vector<std::vector<TrackedObject>> out;
    for (std::size_t i = 0; i < s.frames.size(); ++i) out.push_back(tracker.process(s.time_s[i], s.frames[i]));
    return out;
}

std::vector<std::vector<TruthCentre>> tracking_truth(const Sequence& s) {
    std::vector<std::vector<TruthCentre>> out(s.frames.size());
    for (std::size_t i = 0; i < s.frames.size() && i < s.truth.size(); ++i)
        for (const auto& o : s.truth[i].objects) {
            if (o.returns == 0 || (o.object_class != "drone" && o.object_class != "bird" && o.object_class != "plane")) continue;
            out[i].push_back({o.object_id, o.object_class, truth_box(s, i, o.object_id)->centre});
        }
    return out;
}

SupervisedRun supervised_run(const Sequence& s, const DetectorConfig& config, std::uint32_t target, ScoredBox box, Overlap kind) {
    constexpr std::size_t kSkipAfterFailure = 5;  // VOT: re-initialise five frames after a failure
    SupervisedRun run;
    TargetTracker tracker(config, s.sensor, s.background);
    std::size_t reinit_at = 0;
    // Re-initialised on the ground truth, the tracker can predict that very box from its history
    // for ever: a prediction scores only once a detection since the last (re-)initialisation has
    // confirmed the track, so a tracker that finds nothing scores nothing (and fails), however
    // still its target.
    bool confirmed = false;
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
        const auto truth = truth_box(s, i, target);
        if (!truth) throw InputError("ground_truth.json", "frames[" + std::to_string(i) + "]", "no box for the target");
        if (i == reinit_at) {
            tracker.reset(s.frame_index[i], s.time_s[i], *truth);
            confirmed = false;
            run.iou.push_back(1.0);
            run.initialised.push_back(true);
            continue;
        }
        if (i < reinit_at) {
            run.iou.push_back(0.0);
            run.initialised.push_back(false);
            continue;
        }
        const Detection d = tracker.process(s.frame_index[i], s.time_s[i], s.frames[i], s.boresight[i], frame_intensity(s, i));
        confirmed = confirmed || (d.found && !d.predicted);
        const double iou = confirmed ? overlap(d, box, kind, *truth) : 0.0;
        run.iou.push_back(iou);
        run.initialised.push_back(false);
        if (iou <= 0.0) {
            ++run.failures;
            reinit_at = i + kSkipAfterFailure;
        }
    }
    return run;
}

nlohmann::json dataset_record(const Sequence& s) {
    return {{"directory", std::filesystem::absolute(s.directory).lexically_normal().string()}, {"manifest_id", s.dataset_id}};
}

void check_same_dataset(const nlohmann::json& detections, const std::string& detections_file, const Sequence& s) {
    const auto it = detections.find("dataset");
    if (it == detections.end() || !it->is_object() || !it->contains("manifest_id"))
        throw InputError(detections_file, "dataset", "missing: the file does not say which dataset it was computed on (run detect again)");
    if (it->at("manifest_id") != s.dataset_id) {
        throw InputError(detections_file, "dataset.manifest_id",
                         "these detections are of " + it->value("directory", std::string("another dataset")) + " (manifest " +
                             it->at("manifest_id").dump() + "), not of " + s.directory.string() + " (manifest \"" + s.dataset_id + "\")");
    }
}

nlohmann::json to_json(const Detection& d) {
    nlohmann::json j = box_json(d.box);
    j.update({{"frame", d.frame}, {"time_s", d.time_s}, {"found", d.found}, {"predicted", d.predicted},
              {"sensor_box", box_json(d.sensor_box)}, {"points", d.points}, {"radius_m", d.radius_m}});
    return j;
}

nlohmann::json to_json(const DetectorConfig& c, const SensorGeometry& sensor) {
    return {{"radius_m", c.rbnn_radius_m}, {"lambda", c.lambda.value_or(default_lambda(sensor))},
            {"bias_m", c.bias_m},          {"resolution_m", c.background_resolution_m},
            {"range_tolerance_m", c.background_range_tolerance_m},
            {"min_neighbours", c.min_neighbours}, {"max_diagonal_m", c.max_diagonal_m},
            {"max_speed_mps", c.max_speed_mps},   {"min_box_m", c.min_box_m},
            {"max_object_diagonal_m", c.max_object_diagonal_m},
            {"range_coherence_m", c.range_coherence_m},   {"coherent_fraction", c.coherent_fraction},
            {"target_size_m", vector_json(c.target_size_m)}};
}

DetectorConfig read_detector_config(const nlohmann::json& options, const std::string& file) {
    constexpr double kLarge = 1e9;
    JsonFields f(options, file, "");
    DetectorConfig c;
    c.method = method_from_string(f.choice("method", {"rbnn", "vrbnn", "kalman"}, to_string(c.method)));
    c.rbnn_radius_m = f.number("radius_m", 1e-6, kLarge, c.rbnn_radius_m);
    if (f.has("lambda")) c.lambda = f.number("lambda", 1e-9, kLarge);
    c.bias_m = f.number("bias_m", 0.0, kLarge, c.bias_m);
    c.background_resolution_m = f.number("resolution_m", 1e-6, kLarge, c.background_resolution_m);
    c.background_range_tolerance_m = f.number("range_tolerance_m", 0.0, kLarge, c.background_range_tolerance_m);
    c.min_neighbours = static_cast<int>(f.integer("min_neighbours", 0, 1'000'000, c.min_neighbours));
    c.max_diagonal_m = f.number("max_diagonal_m", 0.0, kLarge, c.max_diagonal_m);
    c.max_speed_mps = f.number("max_speed_mps", 0.0, kLarge, c.max_speed_mps);
    c.min_box_m = f.number("min_box_m", 0.0, kLarge, c.min_box_m);
    c.max_object_diagonal_m = f.number("max_object_diagonal_m", 0.0, kLarge, c.max_object_diagonal_m);
    c.range_coherence_m = f.number("range_coherence_m", 0.0, kLarge, c.range_coherence_m);
    c.coherent_fraction = f.number("coherent_fraction", 0.0, 1.0, c.coherent_fraction);
    if (f.has("target_size_m")) {
        c.target_size_m = f.vec3("target_size_m");
        if (!(c.target_size_m.array() > 0.0).all() || !c.target_size_m.allFinite())
            throw InputError(file, f.path_of("target_size_m"), "three sizes in metres, each above 0");
    }
    f.reject_unknown_keys();
    return c;
}

nlohmann::json detection_report(const Sequence& s, const DetectorConfig& config, std::optional<std::uint32_t> target,
                                const TrackClassifier* classifier) {
    if (!target) target = default_target(s);
    // Checked before any work: a target the ground truth lacks, in the user's terms.
    if (target) check_target(s, *target, s.directory / "ground_truth.json");
    nlohmann::json out = {{"method", to_string(config.method)},
                          {"config", to_json(config, s.sensor)},
                          {"dataset", dataset_record(s)},
                          {"detections", nlohmann::json::array()}};
    for (const auto& d : detect_sequence(s, config)) out["detections"].push_back(to_json(d));
    out["tracks"] = nlohmann::json::array();
    const auto tracked = track_sequence(s, config);
    const auto classes = classifier ? classify_tracks(s.time_s, tracked, *classifier) : std::vector<std::vector<std::optional<TrackClass>>>{};
    for (std::size_t i = 0; i < tracked.size(); ++i) {
        nlohmann::json tracks = nlohmann::json::array();
        const auto& frame = tracked[i];
        for (const TrackedObject& t : frame) {
            nlohmann::json j = box_json(t.box);
            j["track"] = t.track;
            j["sensor_box"] = box_json(t.sensor_box);
            j["points"] = t.points;
            j["predicted"] = t.predicted;
            j["score"] = t.score;
            if (classifier) {
                // Null while the track is too young for a class (kMinClassFrames).
                const std::optional<TrackClass>& c = classes[i][tracks.size()];
                j["class"] = c ? nlohmann::json(track_class_names()[c->index]) : nlohmann::json(nullptr);
                j["class_confidence"] = c ? nlohmann::json(c->confidence) : nlohmann::json(nullptr);
            }
            tracks.push_back(j);
        }
        out["tracks"].push_back({{"frame", s.frame_index[i]}, {"objects", tracks}});
    }
    if (target) out["target"] = *target;
    return out;
}

}  // namespace ladarsim::detect
