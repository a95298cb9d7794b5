// The XGBoost track classifier: learns classes that features separate, and a saved model
// classifies as the trained one did.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <string>
#include <random>

#include "ladarsim/core/input_error.h"
#include "ladarsim/detect/track_classifier.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::detect;

namespace {

// Tracks of each class drawn from distinct feature distributions: drones steady and fast-turning,
// birds flickering at their wingbeat, planes big and fast, clutter erratic.
void synthetic(unsigned seed, int per_class, std::vector<TrackFeatures>& features, std::vector<std::size_t>& labels) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (int i = 0; i < per_class; ++i)
        for (std::size_t c = 0; c < kTrackClassCount; ++c) {
            TrackFeatures f{};
            for (auto& v : f) v = noise(rng);
            f[0] += 6.0f * static_cast<float>(c);          // speed
            f[10] += c == 1 ? 6.0f : 0.0f;                  // flicker at a wingbeat
            f[6] += c == 2 ? 20.0f : c == 3 ? 5.0f : 0.3f;  // extent
            features.push_back(f);
            labels.push_back(c);
        }
}

}  // namespace

TEST_CASE("the classifier learns separable classes, and a saved model gives the same classes and confidences", "[track_classifier]") {
    std::vector<TrackFeatures> train_x, test_x;
    std::vector<std::size_t> train_y, test_y;
    synthetic(1, 100, train_x, train_y);
    synthetic(2, 50, test_x, test_y);
    const TrackClassifier model = TrackClassifier::train(train_x, train_y);
    const std::vector<TrackClass> predicted = model.classify(test_x);
    REQUIRE(predicted.size() == test_x.size());
    int right = 0;
    for (std::size_t i = 0; i < predicted.size(); ++i) {
        right += predicted[i].index == test_y[i];
        CHECK(predicted[i].confidence > 0.25);
        CHECK(predicted[i].confidence <= 1.0);
    }
    CHECK(right >= static_cast<int>(0.95 * static_cast<double>(predicted.size())));

    test::ScratchDir dir;
    model.save(dir / "model.json");
    const TrackClassifier back = TrackClassifier::load(dir / "model.json");
    const std::vector<TrackClass> again = back.classify(test_x);
    for (std::size_t i = 0; i < again.size(); ++i) {
        CHECK(again[i].index == predicted[i].index);
        CHECK(again[i].confidence == Approx(predicted[i].confidence).margin(1e-6));
    }
    // The same data and settings train the same model.
    const std::vector<TrackClass> retrained = TrackClassifier::train(train_x, train_y).classify(test_x);
    for (std::size_t i = 0; i < retrained.size(); ++i) CHECK(retrained[i].confidence == predicted[i].confidence);
}

TEST_CASE("the classifier refuses no data and bad labels, and names a missing or broken model file", "[track_classifier]") {
    CHECK_THROWS_AS(TrackClassifier::train({}, {}), std::invalid_argument);
    CHECK_THROWS_AS(TrackClassifier::train({TrackFeatures{}}, {kTrackClassCount}), std::invalid_argument);
    test::ScratchDir dir;
    CHECK_THROWS_AS(TrackClassifier::load(dir / "absent.json"), InputError);
    {
        std::ofstream(dir / "broken.json") << "{not a model";
    }
    try {
        TrackClassifier::load(dir / "broken.json");
        FAIL("a broken model was read");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("broken.json") != std::string::npos);
    }
    CHECK(track_class_index("bird") == 1u);
    CHECK(track_class_index("tree") == kTrackClassCount);
}

TEST_CASE("the features that separate the classes carry the model's gain", "[track_classifier]") {
    std::vector<TrackFeatures> x;
    std::vector<std::size_t> y;
    synthetic(3, 100, x, y);
    const auto importance = TrackClassifier::train(x, y).feature_importance();
    double total = 0.0;
    for (double v : importance) total += v;
    CHECK(total == Approx(1.0));
    // Speed, extent and flicker separate them; the rest is noise.
    CHECK(importance[0] + importance[6] + importance[10] > 0.9);
}

TEST_CASE("a model trained on other features is refused, naming the file", "[track_classifier]") {
    std::vector<TrackFeatures> x;
    std::vector<std::size_t> y;
    synthetic(4, 20, x, y);
    test::ScratchDir dir;
    TrackClassifier::train(x, y).save(dir / "model.json");
    std::string text;
    {
        std::ifstream in(dir / "model.json");
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    // An older ladarsim's model: one feature it knew by another name.
    const std::string ours = "\"" + std::string(track_feature_names()[9]) + "\"";
    const auto at = text.find(ours);
    REQUIRE(at != std::string::npos);
    text.replace(at, ours.size(), "\"returns_sd\"");
    std::ofstream(dir / "old.json") << text;
    try {
        TrackClassifier::load(dir / "old.json");
        FAIL("a model of other features was read");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("old.json") != std::string::npos);
        CHECK(std::string(e.what()).find("features") != std::string::npos);
    }
}
