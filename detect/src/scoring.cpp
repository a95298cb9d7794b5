#include "ladarsim/detect/scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <Eigen/Geometry>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/detect/box_metrics.h"
#include "ladarsim/detect/expected_overlap.h"
#include "ladarsim/detect/track_classification.h"

namespace ladarsim::detect {

namespace {

constexpr long long kMaxFrame = std::numeric_limits<long long>::max();

/// {"centre_m", "size_m"}: a box's centre, and its extents, none below 0.
OrientedBox read_box(JsonFields& f) {
    OrientedBox b;
    b.centre = f.vec3("centre_m");
    b.size = f.vec3("size_m");
    if (!(b.size.array() >= 0.0).all()) f.fail("size_m", "three extents in metres, none below 0");
    return b;
}

/// "sensor_box" when the entry has one, else its own box (a detector that draws one box).
OrientedBox read_sensor_box(JsonFields& f, const OrientedBox& box) {
    if (!f.has("sensor_box")) return box;
    JsonFields sensor(f.object("sensor_box"), f.file(), f.path_of("sensor_box"));
    const OrientedBox out = read_box(sensor);
    sensor.reject_unknown_keys();
    return out;
}

/// Places the entries of a per-frame list at the dataset's frame each names by "frame": every
/// frame once, in any order.
class FrameMatcher {
public:
    FrameMatcher(const Sequence& s, std::string list, std::string noun, std::size_t entries)
        : s_(s), list_(std::move(list)), noun_(std::move(noun)), entries_(entries) {
        for (std::size_t i = 0; i < s.frame_index.size(); ++i) position_[s.frame_index[i]] = i;
        entry_.assign(s.frame_index.size(), -1);
    }

    /// The dataset position of entry k, whose fields are `f`.
    std::size_t place(JsonFields& f, std::size_t k) {
        const auto frame = static_cast<std::uint64_t>(f.integer("frame", 0, kMaxFrame));
        const auto it = position_.find(frame);
        if (it == position_.end())
            f.fail("frame", "frame " + std::to_string(frame) + " is not one of the " + std::to_string(s_.frame_index.size()) +
                                " frames of " + s_.directory.string() + " (" + std::to_string(s_.frame_index.front()) + " to " +
                                std::to_string(s_.frame_index.back()) + "), and the file holds " + std::to_string(entries_) +
                                " frames: another run's file?");
        if (entry_[it->second] >= 0)
            f.fail("frame", "frame " + std::to_string(frame) + " appears twice (" + list_ + "[" + std::to_string(entry_[it->second]) +
                                "] and " + list_ + "[" + std::to_string(k) + "])");
        entry_[it->second] = static_cast<long long>(k);
        return it->second;
    }

    /// Throws naming the first frame no entry named.
    void check_complete(const std::string& file) const {
        for (std::size_t i = 0; i < entry_.size(); ++i)
            if (entry_[i] < 0)
                throw InputError(file, list_,
                                 "no " + noun_ + " for frame " + std::to_string(s_.frame_index[i]) + " of " + s_.directory.string() +
                                     " (one entry per frame" + (noun_ == "detection" ? ", \"found\": false where nothing was" : "") +
                                     ")");
    }

private:
    const Sequence& s_;
    std::string list_, noun_;
    std::size_t entries_;
    std::map<std::uint64_t, std::size_t> position_;
    std::vector<long long> entry_;
};

std::vector<Detection> read_detections(const Sequence& s, const nlohmann::json& list, const std::string& file) {
    FrameMatcher matcher(s, "detections", "detection", list.size());
    std::vector<Detection> out(s.frames.size());
    for (std::size_t k = 0; k < list.size(); ++k) {
        JsonFields f(list[k], file, "detections[" + std::to_string(k) + "]");
        const std::size_t i = matcher.place(f, k);
        Detection& d = out[i];
        d.frame = s.frame_index[i];
        if (!f.has("found")) f.fail("found", "missing: true where the detector gave a box, false where it gave none");
        d.found = f.boolean("found", false);
        // detect writes a box of zeros where it found nothing: read (and so checked) when present.
        if (d.found || f.has("centre_m") || f.has("size_m")) d.box = read_box(f);
        d.sensor_box = read_sensor_box(f, d.box);
        d.predicted = f.boolean("predicted", false);
        d.time_s = f.number("time_s", -1e12, 1e12, s.time_s[i]);
        d.points = static_cast<std::size_t>(f.integer("points", 0, kMaxFrame, 0));
        d.radius_m = f.number("radius_m", 0.0, 1e9, 0.0);
        f.reject_unknown_keys();
    }
    matcher.check_complete(file);
    return out;
}

std::vector<std::vector<TrackCentre>> read_tracks(const Sequence& s, const nlohmann::json& list, const std::string& file) {
    FrameMatcher matcher(s, "tracks", "tracks entry", list.size());
    std::vector<std::vector<TrackCentre>> out(s.frames.size());
    for (std::size_t k = 0; k < list.size(); ++k) {
        JsonFields f(list[k], file, "tracks[" + std::to_string(k) + "]");
        const std::size_t i = matcher.place(f, k);
        const nlohmann::json& objects = f.array("objects");
        for (std::size_t t = 0; t < objects.size(); ++t) {
            JsonFields o(objects[t], file, f.path_of("objects") + "[" + std::to_string(t) + "]");
            TrackCentre h;
            h.track = static_cast<std::uint32_t>(o.integer("track", 0, std::numeric_limits<std::uint32_t>::max()));
            const OrientedBox box = read_box(o);
            h.centre = read_sensor_box(o, box).centre;  // the sensor-aware box's centre, as for the target
            h.score = o.number("score", -1e300, 1e300);
            o.integer("points", 0, kMaxFrame, 0);
            o.boolean("predicted", false);
            // A track too young for a class carries null for both (track_classification.h's kMinClassFrames).
            if (o.null("class")) {
                if (o.has("class_confidence") && !o.null("class_confidence"))
                    o.fail("class_confidence", "must be null where class is (a track too young for a class)");
            } else if (o.has("class")) {
                std::vector<std::string> names(track_class_names().begin(), track_class_names().end());
                o.choice("class", names, "");
                o.number("class_confidence", 0.0, 1.0);
            }
            o.reject_unknown_keys();
            out[i].push_back(h);
        }
        f.reject_unknown_keys();
    }
    matcher.check_complete(file);
    return out;
}

/// Older `detect` reports carry the supervised runs they made: checked so that a malformed claim
/// is refused by name, never scored (eval scores boxes; the protocol needs the tracker).
void check_supervised_block(const nlohmann::json& block, const std::string& file, std::size_t frames) {
    JsonFields f(block, file, "supervised");
    for (const auto& [name, box, kind] : scored_kinds()) {
        if (!f.has(name)) continue;
        JsonFields run(f.object(name), file, f.path_of(name));
        const nlohmann::json& iou = run.array("iou");
        const nlohmann::json& initialised = run.array("initialised");
        for (const auto* list : {&iou, &initialised})
            if (list->size() != frames)
                run.fail(list == &iou ? "iou" : "initialised",
                         "holds " + std::to_string(list->size()) + " frames, the detections " + std::to_string(frames));
        for (std::size_t k = 0; k < frames; ++k) {
            const std::string at = "[" + std::to_string(k) + "]";
            if (!iou[k].is_number() || !(iou[k].get<double>() >= 0.0 && iou[k].get<double>() <= 1.0))
                throw InputError(file, run.path_of("iou") + at, iou[k].dump() + " is not an overlap (0 to 1)");
            if (!initialised[k].is_boolean())
                throw InputError(file, run.path_of("initialised") + at, "expected true or false, found " + initialised[k].dump());
        }
        run.integer("failures", 0, static_cast<long long>(frames));
        run.reject_unknown_keys();
    }
    f.reject_unknown_keys();
}

/// Per frame, the rotation from the sensor frame to one whose z is up (the world's axes about the
/// sensor), from a ground-truth object's two boxes: a tilted mount tilts the sensor frame.
std::vector<Eigen::Quaterniond> level_rotations(const Sequence& s) {
    std::vector<Eigen::Quaterniond> out(s.frames.size(), Eigen::Quaterniond::Identity());
    for (std::size_t i = 0; i < s.frames.size() && i < s.truth.size(); ++i)
        if (!s.truth[i].objects.empty()) {
            const auto& o = s.truth[i].objects.front();
            out[i] = (o.box_world.orientation * o.box_sensor.orientation.conjugate()).normalized();
        }
    return out;
}

/// One-pass scores of the target's boxes, one per frame of the dataset.
nlohmann::json evaluate(const Sequence& s, const std::vector<Detection>& detections, std::uint32_t target) {
    nlohmann::json per_frame = nlohmann::json::array();
    double l2_sum = 0.0;
    int l2_count = 0, lost = 0;
    std::map<std::string, double> iou_sum;
    std::vector<double> ious, l2s;
    for (std::size_t i = 0; i < detections.size(); ++i) {
        const auto truth = truth_box(s, i, target);
        if (!truth) throw InputError("ground_truth.json", "frames[" + std::to_string(i) + "]", "no box for the target");
        const Detection& d = detections[i];
        std::map<std::string, double> iou;
        for (const auto& [name, box, kind] : scored_kinds()) {
            iou[name] = overlap(d, box, kind, *truth);
            iou_sum[name] += iou[name];
        }
        const double l2 = d.found ? centre_distance_m(d.box, *truth) : std::numeric_limits<double>::infinity();
        ious.push_back(iou["sensor_3d"]);
        l2s.push_back(l2);
        if (d.found) {
            l2_sum += l2;
            ++l2_count;
        }
        if (iou["sensor_3d"] <= 0.0) ++lost;
        per_frame.push_back({{"frame", d.frame}, {"found", d.found}, {"predicted", d.predicted}, {"iou", iou["sensor_3d"]},
                             {"iou_bev", iou["sensor_bev"]}, {"points_iou", iou["points_3d"]}, {"points_iou_bev", iou["points_bev"]},
                             {"l2_m", d.found ? nlohmann::json(l2) : nlohmann::json(nullptr)}});
    }
    const auto n = static_cast<double>(detections.size());
    // One-pass success (fraction of frames with IoU >= t, 21 thresholds) and precision (L2 <= d).
    nlohmann::json success = nlohmann::json::array(), precision = nlohmann::json::object();
    double auc = 0.0;
    for (int k = 0; k <= 20; ++k) {
        const double t = k / 20.0;
        const double fraction = std::count_if(ious.begin(), ious.end(), [&](double v) { return v >= t && v > 0.0; }) / n;
        success.push_back({{"threshold", t}, {"fraction", fraction}});
        auc += fraction / 21.0;
    }
    for (double d : {0.2, 0.5, 1.0, 2.0})
        precision[std::to_string(d).substr(0, 3) + "_m"] = std::count_if(l2s.begin(), l2s.end(), [&](double v) { return v <= d; }) / n;
    return {{"target", target},
            {"frames", detections.size()},
            {"mean_l2_m", l2_count ? nlohmann::json(l2_sum / l2_count) : nlohmann::json(nullptr)},
            {"mean_iou", iou_sum["sensor_3d"] / n},
            {"mean_iou_bev", iou_sum["sensor_bev"] / n},
            {"frames_lost", lost},
            {"point_box", {{"mean_iou", iou_sum["points_3d"] / n}, {"mean_iou_bev", iou_sum["points_bev"] / n}}},
            {"success_auc", auc},
            {"success", success},
            {"precision", precision},
            {"per_frame", per_frame}};
}

/// CLEAR MOT and centre-distance AP of the tracks against every drone, bird and aircraft.
void add_tracking_scores(const Sequence& s, std::vector<std::vector<TrackCentre>> hypotheses, nlohmann::json& scores) {
    auto truth = tracking_truth(s);
    // Centres about the sensor with z up: nuScenes' AP measures on the ground plane.
    const auto level = level_rotations(s);
    for (std::size_t f = 0; f < truth.size(); ++f) {
        for (auto& o : truth[f]) o.centre = level[f] * o.centre;
        for (auto& h : hypotheses[f]) h.centre = level[f] * h.centre;
    }
    constexpr double kGate_m = 2.0;
    const ClearMot mot = clear_mot(truth, hypotheses, kGate_m);
    auto number = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
    nlohmann::json per_class = nlohmann::json::object();
    for (const auto& [cls, c] : mot.per_class)
        per_class[cls] = {{"objects", c.objects}, {"matches", c.matches}, {"misses", c.misses}, {"id_switches", c.id_switches},
                          {"recall", c.objects ? nlohmann::json(double(c.matches) / c.objects) : nlohmann::json(nullptr)},
                          {"motp_m", c.matches ? nlohmann::json(c.distance_sum_m / c.matches) : nlohmann::json(nullptr)}};
    const CentreDistanceAp aps = centre_distance_aps(truth, hypotheses, CentreDistance::ground_plane);
    const CentreDistanceAp aps_3d = centre_distance_aps(truth, hypotheses, CentreDistance::three_d);
    nlohmann::json ap = nlohmann::json::object();
    for (std::size_t k = 0; k < aps.at.size(); ++k)
        ap[std::to_string(CentreDistanceAp::kThresholds_m[k]).substr(0, 4) + "_m"] = number(aps.at[k]);
    scores["mota"] = number(mot.mota());
    scores["motp_m"] = number(mot.motp_m());
    scores["id_switches"] = mot.all.id_switches;
    scores["ap_centre"] = number(aps.mean);
    scores["ap_centre_3d"] = number(aps_3d.mean);
    scores["tracking"] = {{"gate_m", kGate_m},        {"objects", mot.all.objects},  {"matches", mot.all.matches},
                          {"misses", mot.all.misses}, {"false_positives", mot.false_positives},
                          {"ap_centre_at", ap},       {"per_class", per_class}};
}

}  // namespace

DetectionsFile read_detections_file(const Sequence& s, const nlohmann::json& report, const std::string& file) {
    JsonFields top(report, file, "");
    check_same_dataset(report, file, s);
    top.object("dataset");
    DetectionsFile out;
    out.method = top.string("method", "");
    if (top.has("config")) top.object("config");  // the detector's settings: recorded, not scored
    const auto target = top.has("target") ? std::optional<std::uint32_t>(static_cast<std::uint32_t>(
                                                top.integer("target", 1, std::numeric_limits<std::uint32_t>::max())))
                                          : default_target(s);
    const std::string truth_file = (s.directory / "ground_truth.json").string();
    if (!target)
        throw InputError(file, "target",
                         s.truth.empty() ? "none: nothing to score, the dataset has no ground truth (a recorded dataset)"
                                         : "none: nothing to score, the ground truth has no drone to take as the target; name one "
                                           "of its objects (" + truth_file + ") in the file's \"target\", as `ladarsim detect "
                                           "--target ID` does");
    check_target(s, *target, truth_file);
    out.target = *target;
    out.detections = read_detections(s, top.array("detections"), file);
    if (top.has("tracks")) out.tracks = read_tracks(s, top.array("tracks"), file);
    if (top.has("supervised")) {
        check_supervised_block(top.object("supervised"), file, out.detections.size());
        out.has_supervised_block = true;
    }
    top.reject_unknown_keys();
    return out;
}

nlohmann::json evaluate_report(const Sequence& s, const nlohmann::json& report, const std::string& file) {
    const DetectionsFile in = read_detections_file(s, report, file);
    nlohmann::json scores = evaluate(s, in.detections, in.target);
    scores["method"] = in.method;
    scores["measures"] = {"average_overlap", "l2"};
    if (in.tracks) {
        add_tracking_scores(s, *in.tracks, scores);
        scores["measures"].push_back("mot");
        scores["measures"].push_back("ap");
        const nlohmann::json classification = classification_scores(s, report.at("tracks"));
        if (!classification.is_null()) {
            scores["classification"] = classification;
            scores["measures"].push_back("classification");
        }
    }
    if (in.has_supervised_block) scores["ignored"] = {"supervised"};
    return scores;
}

nlohmann::json benchmark_report(const Sequence& s, const DetectorConfig& config, std::optional<std::uint32_t> target) {
    if (!target) target = default_target(s);
    const std::string truth_file = (s.directory / "ground_truth.json").string();
    if (!target)
        throw InputError(truth_file, "--target",
                         s.truth.empty() ? "no ground truth (a recorded dataset): nothing to score against"
                                         : "no drone in the ground truth to default to: name the target to benchmark");
    nlohmann::json scores = evaluate_report(s, detection_report(s, config, target), "(" + to_string(config.method) + " run)");
    const SupervisedRuns runs = supervised_runs(s, config, *target);
    const auto interval = vot_length_interval({static_cast<int>(s.frames.size())});
    auto eao = [&](const std::string& name) {
        const SupervisedRun& run = runs.at(name);
        return expected_average_overlap(fragments_of(run.iou, run.initialised), interval.first, interval.second);
    };
    scores["eao"] = eao("sensor_3d");
    scores["eao_bev"] = eao("sensor_bev");
    scores["eao_interval"] = {interval.first, interval.second};
    scores["failures"] = runs.at("sensor_3d").failures;
    scores["point_box"]["eao"] = eao("points_3d");
    scores["point_box"]["eao_bev"] = eao("points_bev");
    scores["point_box"]["failures"] = runs.at("points_3d").failures;
    const SupervisedRun& headline = runs.at("sensor_3d");
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
        scores["per_frame"][i]["supervised_iou"] = headline.iou[i];
        scores["per_frame"][i]["initialised"] = static_cast<bool>(headline.initialised[i]);
    }
    scores["measures"].push_back("eao");
    return scores;
}

}  // namespace ladarsim::detect
