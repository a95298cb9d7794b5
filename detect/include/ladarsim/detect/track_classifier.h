#pragma once
// Which kind of thing a track follows, from its features (track_features.h): gradient-boosted
// trees (XGBoost) trained on rendered campaigns, saved and loaded as XGBoost's JSON model.
#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ladarsim/detect/track_features.h"

namespace ladarsim::detect {

/// The classes a track is given: the project's moving target classes, and clutter (a track that
/// follows none of them: cloud backscatter, false alarms, the map's leftovers).
inline constexpr std::size_t kTrackClassCount = 4;
const std::array<std::string_view, kTrackClassCount>& track_class_names();  ///< drone, bird, plane, clutter
/// Index of a class name in track_class_names(); kTrackClassCount for any other name.
std::size_t track_class_index(std::string_view name);

struct TrackClass {
    std::size_t index = 0;     ///< into track_class_names()
    double confidence = 0.0;   ///< the model's probability of that class
};

struct ClassifierTraining {
    int rounds = 60;
    int max_depth = 4;
    double learning_rate = 0.3;
    unsigned seed = 0;
};

class TrackClassifier {
public:
    /// Trains on `features` (one row each) with `labels` (indices into track_class_names()).
    /// Throws std::invalid_argument for no rows or a label out of range.
    static TrackClassifier train(const std::vector<TrackFeatures>& features, const std::vector<std::size_t>& labels,
                                 const ClassifierTraining& settings = {});
    /// Reads a model that save() wrote. Throws InputError naming the file when it is missing, is no
    /// model, or was trained on other features than track_feature_names().
    static TrackClassifier load(const std::filesystem::path& file);

    TrackClassifier(TrackClassifier&&) noexcept;
    TrackClassifier& operator=(TrackClassifier&&) noexcept;
    ~TrackClassifier();

    /// Writes the model (XGBoost JSON) to a temporary name and renames it into place.
    void save(const std::filesystem::path& file) const;
    /// What each feature (track_feature_names() order) did for the model: its share of the total
    /// gain of the splits on it (summing to 1; 0 for a feature no split uses).
    std::array<double, kTrackFeatureCount> feature_importance() const;
    /// The most probable class of each row.
    std::vector<TrackClass> classify(const std::vector<TrackFeatures>& features) const;

private:
    struct Booster;
    explicit TrackClassifier(std::unique_ptr<Booster> booster);
    std::unique_ptr<Booster> booster_;
};

}  // namespace ladarsim::detect
