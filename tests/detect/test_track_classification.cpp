// What a track follows: the label a track is trained on and scored against.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "ladarsim/detect/track_classification.h"
#include "ladarsim/detect/track_classifier.h"

using namespace ladarsim::detect;

namespace {

TrackHistory track_at(const Eigen::Vector3d& centre, std::size_t frames) {
    TrackHistory h;
    for (std::size_t i = 0; i < frames; ++i) {
        TrackSample s;
        s.time_s = 0.05 * static_cast<double>(i);
        s.centre = centre;
        s.points = 20;
        h.frames.push_back(i);
        h.samples.push_back(s);
    }
    return h;
}

std::string class_name(std::size_t index) { return std::string(track_class_names()[index]); }

}  // namespace

TEST_CASE("a track on an aircraft's wing, metres from its centre, follows the aircraft", "[track_classification]") {
    // A 10 m light aircraft at 1.5 km; the track is on a wing tip, 4 m from the aircraft's centre
    // (beyond the 2 m gate), inside its box.
    const std::vector<std::vector<FollowableObject>> truth(
        6, {FollowableObject{"plane", {1500.0, 0.0, 80.0}, {7.0, 10.0, 2.5}}});
    CHECK(class_name(followed_class(track_at({1500.0, 4.0, 80.3}, 6), truth)) == "plane");
    // Beside the box and beyond the gate it follows nothing.
    CHECK(class_name(followed_class(track_at({1500.0, 7.0, 80.3}, 6), truth)) == "clutter");
}

TEST_CASE("a track follows the nearest object in most of its frames, and predicted frames do not vote", "[track_classification]") {
    std::vector<std::vector<FollowableObject>> truth(10);
    for (std::size_t i = 0; i < 10; ++i) {
        truth[i].push_back({"drone", {400.0, 0.0, 30.0}, {0.3, 0.3, 0.06}});
        // A bird 1.5 m away: within the gate too, but farther than the drone.
        truth[i].push_back({"bird", {401.5, 0.0, 30.0}, {0.4, 0.4, 0.1}});
    }
    TrackHistory h = track_at({400.2, 0.0, 30.0}, 10);
    CHECK(class_name(followed_class(h, truth)) == "drone");
    // Frames 0-5 nearer the bird, but four of them predicted: the drone still has most votes.
    for (std::size_t i = 0; i < 6; ++i) {
        h.samples[i].centre = {401.4, 0.0, 30.0};
        h.samples[i].predicted = i < 4;
    }
    CHECK(class_name(followed_class(h, truth)) == "drone");
    h.samples[4].centre = h.samples[5].centre = h.samples[6].centre = {401.4, 0.0, 30.0};
    h.samples[0].predicted = h.samples[1].predicted = h.samples[2].predicted = h.samples[3].predicted = false;
    CHECK(class_name(followed_class(h, truth)) == "bird");
}

TEST_CASE("a track gets a class from its kMinClassFrames-th frame with a cluster on, none before", "[track_classification]") {
    // Any model will do: what is checked is which tracks it is asked about.
    std::vector<TrackFeatures> x(8, TrackFeatures{});
    std::vector<std::size_t> y{0, 1, 2, 3, 0, 1, 2, 3};
    for (std::size_t i = 0; i < x.size(); ++i) x[i][0] = static_cast<float>(i);
    const TrackClassifier model = TrackClassifier::train(x, y);
    // Track 1 from frame 0, unseen (predicted) in frame 2; track 2 from frame 3. 20 Hz.
    const std::size_t frames = kMinClassFrames + 5;
    std::vector<double> time_s;
    std::vector<std::vector<TrackedObject>> tracked(frames);
    for (std::size_t i = 0; i < frames; ++i) {
        time_s.push_back(0.05 * static_cast<double>(i));
        for (std::uint32_t track : {1u, 2u}) {
            if (track == 2 && i < 3) continue;
            TrackedObject t;
            t.track = track;
            t.box.centre = {400.0 + 0.3 * static_cast<double>(i), 10.0 * track, 30.0};
            t.box.size = {0.3, 0.3, 0.1};
            t.predicted = track == 1 && i == 2;
            t.points = t.predicted ? 0 : 20 + i % 3;
            tracked[i].push_back(t);
        }
    }
    const auto classes = classify_tracks(time_s, tracked, model);
    REQUIRE(classes.size() == frames);
    for (std::size_t i = 0; i < frames; ++i) {
        REQUIRE(classes[i].size() == tracked[i].size());
        for (std::size_t k = 0; k < tracked[i].size(); ++k) {
            const std::size_t seen = tracked[i][k].track == 2 ? i - 2 : (i < 2 ? i + 1 : i);
            CHECK(classes[i][k].has_value() == (seen >= kMinClassFrames));
        }
    }
}
