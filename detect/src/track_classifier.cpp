#include "ladarsim/detect/track_classifier.h"

#include <limits>
#include <string>
#include <vector>
#include <stdexcept>
#include <system_error>

#include <xgboost/c_api.h>

#include "ladarsim/core/input_error.h"

namespace ladarsim::detect {
namespace {

// XGBoost's C API returns -1 and keeps the message for XGBGetLastError.
void check(int status, const char* what) {
    if (status != 0) throw std::runtime_error(std::string("XGBoost: ") + what + ": " + XGBGetLastError());
}

struct Matrix {
    DMatrixHandle handle = nullptr;
    explicit Matrix(const std::vector<TrackFeatures>& rows) {
        std::vector<float> data;
        data.reserve(rows.size() * kTrackFeatureCount);
        for (const TrackFeatures& r : rows) data.insert(data.end(), r.begin(), r.end());
        // NaN marks a missing value; our features are never NaN.
        check(XGDMatrixCreateFromMat(data.data(), rows.size(), kTrackFeatureCount, std::numeric_limits<float>::quiet_NaN(), &handle),
              "making a feature matrix");
    }
    ~Matrix() { XGDMatrixFree(handle); }
    Matrix(const Matrix&) = delete;
    Matrix& operator=(const Matrix&) = delete;
};

}  // namespace

struct TrackClassifier::Booster {
    BoosterHandle handle = nullptr;
    Booster() { check(XGBoosterCreate(nullptr, 0, &handle), "creating a booster"); }
    ~Booster() { XGBoosterFree(handle); }
    Booster(const Booster&) = delete;
    Booster& operator=(const Booster&) = delete;
};

const std::array<std::string_view, kTrackClassCount>& track_class_names() {
    static const std::array<std::string_view, kTrackClassCount> names = {"drone", "bird", "plane", "clutter"};
    return names;
}

std::size_t track_class_index(std::string_view name) {
    const auto& names = track_class_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return i;
    return kTrackClassCount;
}

TrackClassifier::TrackClassifier(std::unique_ptr<Booster> booster) : booster_(std::move(booster)) {}
TrackClassifier::TrackClassifier(TrackClassifier&&) noexcept = default;
TrackClassifier& TrackClassifier::operator=(TrackClassifier&&) noexcept = default;
TrackClassifier::~TrackClassifier() = default;

TrackClassifier TrackClassifier::train(const std::vector<TrackFeatures>& features, const std::vector<std::size_t>& labels,
                                       const ClassifierTraining& settings) {
    if (features.empty()) throw std::invalid_argument("TrackClassifier::train: no tracks to train on");
    if (labels.size() != features.size()) throw std::invalid_argument("TrackClassifier::train: features and labels differ in number");
    std::vector<float> label_values;
    for (std::size_t l : labels) {
        if (l >= kTrackClassCount) throw std::invalid_argument("TrackClassifier::train: label out of range");
        label_values.push_back(static_cast<float>(l));
    }
    Matrix train(features);
    check(XGDMatrixSetFloatInfo(train.handle, "label", label_values.data(), label_values.size()), "setting labels");
    auto booster = std::make_unique<Booster>();
    XGBoosterFree(booster->handle);
    check(XGBoosterCreate(&train.handle, 1, &booster->handle), "creating a booster");
    const auto set = [&](const char* key, const std::string& value) { check(XGBoosterSetParam(booster->handle, key, value.c_str()), key); };
    set("objective", "multi:softprob");
    set("num_class", std::to_string(kTrackClassCount));
    set("max_depth", std::to_string(settings.max_depth));
    set("eta", std::to_string(settings.learning_rate));
    set("seed", std::to_string(settings.seed));
    // One thread: the same model from the same data on every machine. The histogram method: Debian's
    // XGBoost 1.6 with the exact method gave some rows between the classes equal margins for every
    // class (probability 0.25 each), where hist's are those of the nearest class.
    set("nthread", "1");
    set("tree_method", "hist");
    set("verbosity", "0");
    // Named, so that the model carries the names of the features it was trained on.
    const std::vector<std::string> names(track_feature_names().begin(), track_feature_names().end());
    std::vector<const char*> c_names;
    for (const std::string& n : names) c_names.push_back(n.c_str());
    check(XGBoosterSetStrFeatureInfo(booster->handle, "feature_name", c_names.data(), c_names.size()), "naming the features");
    for (int i = 0; i < settings.rounds; ++i) check(XGBoosterUpdateOneIter(booster->handle, i, train.handle), "training");
    return TrackClassifier(std::move(booster));
}

TrackClassifier TrackClassifier::load(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file.string(), "file", "does not exist or is not a regular file");
    auto booster = std::make_unique<Booster>();
    if (XGBoosterLoadModel(booster->handle, file.c_str()) != 0) throw InputError(file.string(), "model", XGBGetLastError());
    check(XGBoosterSetParam(booster->handle, "nthread", "1"), "nthread");
    // A model trained on other features (an older ladarsim's) would read ours as its own.
    bst_ulong count = 0;
    const char** names = nullptr;
    check(XGBoosterGetStrFeatureInfo(booster->handle, "feature_name", &count, &names), "reading the feature names");
    const auto& ours = track_feature_names();
    bool same = count == ours.size();
    for (bst_ulong i = 0; same && i < count; ++i) same = names[i] == ours[i];
    if (!same)
        throw InputError(file.string(), "features",
                         "the model was trained on other track features than this ladarsim computes: train it again (`ladarsim train-classifier`)");
    return TrackClassifier(std::move(booster));
}

void TrackClassifier::save(const std::filesystem::path& file) const {
    // XGBoost picks its JSON format from the name's .json.
    const std::filesystem::path tmp = file.string() + ".tmp.json";
    if (XGBoosterSaveModel(booster_->handle, tmp.c_str()) != 0) throw InputError(file.string(), "write", XGBGetLastError());
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) throw InputError(file.string(), "write", ec.message());
}

std::array<double, kTrackFeatureCount> TrackClassifier::feature_importance() const {
    bst_ulong count = 0, dim = 0;
    const char** names = nullptr;
    const bst_ulong* shape = nullptr;
    const float* scores = nullptr;
    check(XGBoosterFeatureScore(booster_->handle, R"({"importance_type": "total_gain"})", &count, &names, &dim, &shape, &scores),
          "scoring the features");
    std::array<double, kTrackFeatureCount> out{};
    const auto& ours = track_feature_names();
    double total = 0.0;
    // Only the features some split uses are listed.
    for (bst_ulong i = 0; i < count; ++i)
        for (std::size_t k = 0; k < kTrackFeatureCount; ++k)
            if (ours[k] == names[i]) out[k] = scores[i], total += scores[i];
    if (total > 0.0)
        for (double& v : out) v /= total;
    return out;
}

std::vector<TrackClass> TrackClassifier::classify(const std::vector<TrackFeatures>& features) const {
    std::vector<TrackClass> out;
    if (features.empty()) return out;
    Matrix rows(features);
    bst_ulong length = 0;
    const float* p = nullptr;
    check(XGBoosterPredict(booster_->handle, rows.handle, 0, 0, 0, &length, &p), "classifying");
    if (length != features.size() * kTrackClassCount) throw std::runtime_error("XGBoost: prediction has the wrong size");
    for (std::size_t r = 0; r < features.size(); ++r) {
        TrackClass best;
        for (std::size_t c = 0; c < kTrackClassCount; ++c) {
            const double prob = p[r * kTrackClassCount + c];
            if (prob > best.confidence) best = {c, prob};
        }
        out.push_back(best);
    }
    return out;
}

}  // namespace ladarsim::detect
