#include "ladarsim/detect/track_classification.h"

#include <algorithm>
#include <limits>
#include <map>

#include "ladarsim/detect/sequence.h"
#include "ladarsim/detect/tracking_metrics.h"

namespace ladarsim::detect {
namespace {

TrackSample sample_of(double time_s, const TrackedObject& t) {
    return TrackSample{time_s, t.box.centre, t.box.size, t.points, t.predicted};
}

nlohmann::json ratio(int numerator, int denominator) {
    return denominator > 0 ? nlohmann::json(static_cast<double>(numerator) / denominator) : nlohmann::json(nullptr);
}

// Frames with a cluster: a predicted frame measures nothing.
std::size_t frames_seen(const std::vector<TrackSample>& samples) {
    return static_cast<std::size_t>(std::count_if(samples.begin(), samples.end(), [](const TrackSample& t) { return !t.predicted; }));
}

}  // namespace

std::vector<TrackHistory> track_histories(const std::vector<double>& time_s, const std::vector<std::vector<TrackedObject>>& tracked) {
    std::vector<TrackHistory> out;
    std::map<std::uint32_t, std::size_t> index;
    for (std::size_t i = 0; i < tracked.size(); ++i)
        for (const TrackedObject& t : tracked[i]) {
            auto [it, inserted] = index.emplace(t.track, out.size());
            if (inserted) out.push_back(TrackHistory{t.track, {}, {}});
            TrackHistory& h = out[it->second];
            h.frames.push_back(i);
            h.samples.push_back(sample_of(time_s[i], t));
        }
    return out;
}

std::vector<std::vector<FollowableObject>> followable_truth(const Sequence& s) {
    std::vector<std::vector<FollowableObject>> out;
    const auto truth = tracking_truth(s);
    for (std::size_t i = 0; i < truth.size(); ++i) {
        out.emplace_back();
        for (const TruthCentre& o : truth[i]) {
            const auto box = truth_box(s, i, o.id);
            out.back().push_back({o.object_class, o.centre, box ? box->size : Eigen::Vector3d::Zero()});
        }
    }
    return out;
}

std::size_t followed_class(const TrackHistory& history, const std::vector<std::vector<FollowableObject>>& truth) {
    std::array<int, kTrackClassCount> votes{};
    for (std::size_t k = 0; k < history.frames.size(); ++k) {
        const TrackSample& s = history.samples[k];
        if (s.predicted) continue;
        const std::size_t frame = history.frames[k];
        const FollowableObject* nearest = nullptr;
        double best = std::numeric_limits<double>::infinity();
        if (frame < truth.size())
            for (const FollowableObject& o : truth[frame]) {
                const Eigen::Vector3d offset = s.centre - o.centre;
                const bool inside = (offset.cwiseAbs().array() <= 0.5 * o.size.array()).all();
                const double d = offset.norm();
                if ((d <= kFollowGate_m || inside) && d < best) best = d, nearest = &o;
            }
        const std::size_t c = nearest ? track_class_index(nearest->object_class) : track_class_index("clutter");
        ++votes[std::min(c, kTrackClassCount - 1)];
    }
    return static_cast<std::size_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

void add_training_rows(const Sequence& s, const DetectorConfig& config, std::vector<TrackFeatures>& features,
                       std::vector<std::size_t>& labels) {
    const auto truth = followable_truth(s);
    for (const TrackHistory& h : track_histories(s.time_s, track_sequence(s, config))) {
        const std::size_t label = followed_class(h, truth);
        std::vector<TrackSample> prefix;
        // Doubling up to the feature window, then a window's half at a time; only where the track
        // is given a class (a row of a younger one would teach what its length says).
        for (std::size_t n = 4; n < h.samples.size(); n += std::min(n, kTrackFeatureFrames / 2)) {
            prefix.assign(h.samples.begin(), h.samples.begin() + static_cast<std::ptrdiff_t>(n));
            if (frames_seen(prefix) < kMinClassFrames) continue;
            features.push_back(track_features(prefix));
            labels.push_back(label);
        }
        if (frames_seen(h.samples) < kMinClassFrames) continue;
        features.push_back(track_features(h.samples));
        labels.push_back(label);
    }
}

std::vector<std::vector<std::optional<TrackClass>>> classify_tracks(const std::vector<double>& time_s,
                                                                    const std::vector<std::vector<TrackedObject>>& tracked,
                                                                    const TrackClassifier& classifier) {
    std::map<std::uint32_t, std::vector<TrackSample>> so_far;
    std::vector<std::vector<std::optional<TrackClass>>> out;
    for (std::size_t i = 0; i < tracked.size(); ++i) {
        std::vector<TrackFeatures> rows;
        std::vector<std::size_t> row_of;
        for (std::size_t k = 0; k < tracked[i].size(); ++k) {
            auto& samples = so_far[tracked[i][k].track];
            samples.push_back(sample_of(time_s[i], tracked[i][k]));
            if (frames_seen(samples) < kMinClassFrames) continue;
            row_of.push_back(k);
            rows.push_back(track_features(samples));
        }
        out.emplace_back(tracked[i].size());
        const std::vector<TrackClass> classes = classifier.classify(rows);
        for (std::size_t r = 0; r < rows.size(); ++r) out.back()[row_of[r]] = classes[r];
    }
    return out;
}

nlohmann::json classification_scores(const Sequence& s, const nlohmann::json& tracks) {
    // Each track's history, and its class in each frame, from the report.
    std::map<std::uint64_t, std::size_t> slot;
    for (std::size_t i = 0; i < s.frame_index.size(); ++i) slot[s.frame_index[i]] = i;
    std::map<std::uint32_t, TrackHistory> histories;
    std::map<std::uint32_t, std::vector<std::size_t>> classes;
    bool any_class = false;
    for (const auto& entry : tracks) {
        const auto it = slot.find(entry.at("frame").get<std::uint64_t>());
        if (it == slot.end()) continue;
        for (const auto& o : entry.at("objects")) {
            if (!o.contains("class")) continue;
            any_class = true;
            const auto track = o.at("track").get<std::uint32_t>();
            TrackHistory& h = histories[track];
            h.track = track;
            h.frames.push_back(it->second);
            const auto& c = o.at("centre_m");
            TrackSample sample;
            sample.centre = {c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>()};
            sample.predicted = o.value("predicted", false);
            h.samples.push_back(sample);
            // Null: too young for a class (kMinClassFrames); kTrackClassCount stands for it.
            const auto& c_name = o.at("class");
            classes[track].push_back(c_name.is_null() ? kTrackClassCount : track_class_index(c_name.get<std::string>()));
        }
    }
    if (!any_class) return nullptr;
    const auto truth = followable_truth(s);
    const auto& names = track_class_names();
    std::array<std::array<int, kTrackClassCount>, kTrackClassCount> confusion{};
    std::array<int, kTrackClassCount> unclassified{};
    std::vector<double> settle;
    for (const auto& [track, h] : histories) {
        std::vector<std::size_t> c = classes[track];
        c.erase(std::remove(c.begin(), c.end(), kTrackClassCount), c.end());
        const std::size_t truth_class = followed_class(h, truth);
        if (classes[track].back() == kTrackClassCount) {
            ++unclassified[truth_class];
            continue;
        }
        ++confusion[truth_class][std::min(c.back(), kTrackClassCount - 1)];
        std::size_t last_change = 0;
        for (std::size_t k = 1; k < c.size(); ++k)
            if (c[k] != c[k - 1]) last_change = k;
        settle.push_back(static_cast<double>(last_change + 1));
    }
    nlohmann::json per_class = nlohmann::json::object(), matrix = nlohmann::json::object(), without = nlohmann::json::object();
    for (std::size_t t = 0; t < kTrackClassCount; ++t) {
        int row = 0, column = 0;
        for (std::size_t p = 0; p < kTrackClassCount; ++p) {
            row += confusion[t][p];
            column += confusion[p][t];
            matrix[std::string(names[t])][std::string(names[p])] = confusion[t][p];
        }
        without[std::string(names[t])] = unclassified[t];
        per_class[std::string(names[t])] = {{"tracks", row}, {"called", column}, {"precision", ratio(confusion[t][t], column)},
                                            {"recall", ratio(confusion[t][t], row)}};
    }
    std::sort(settle.begin(), settle.end());
    double mean = 0.0;
    for (double v : settle) mean += v / static_cast<double>(settle.size());
    const nlohmann::json settling = settle.empty() ? nlohmann::json(nullptr) : nlohmann::json{{"mean", mean}, {"median", settle[settle.size() / 2]}};
    return {{"tracks", histories.size()},
            {"per_class", per_class},
            {"confusion", matrix},
            {"unclassified", without},
            {"frames_to_settle", settling}};
}

}  // namespace ladarsim::detect
