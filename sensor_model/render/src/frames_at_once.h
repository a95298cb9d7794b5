#pragma once
// Several frames of a run rendered at once, each by its own renderer.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/waveform_file.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::sensor_model {

/// How many frames to render at once on `threads` threads, `frames` being all this process has
/// to render. A frame of a light scene is a few milliseconds of tasks of uneven cost (a drone's
/// beams cost 30 times the sky's): 16 threads on one frame waited for its slowest stretch, and the
/// default scenario's render ran 3.7x faster than on one thread. A frame per four threads keeps
/// them busy; up to 7 threads render one frame at a time, as a run always did. Each frame at once
/// holds its own renderer (its traced scene and buffers: 4 MB more a frame for the default
/// scenario, 34 MB for dataset 2 over Autzen).
int frames_at_once(int threads, int frames);

/// A frame as rendered: `failure` says why not ("" when it was).
struct RenderedFrame {
    Frame frame;
    std::optional<FrameWaveforms> waveforms;
    /// The seconds of the run this frame accounts for: frames rendered together share their wall
    /// time in proportion to their own, so that a run's frames add up to its rendering time.
    double render_s = 0.0;
    std::string failure;
};

/// Renders frames a batch at a time, each frame of a batch by its own renderer (the first being
/// the run's own), their beams' tasks shared among all threads. Output does not depend on how
/// frames are batched: a frame depends only on the scenario, the seed and its index.
class FrameBatch {
public:
    /// `first`: the run's renderer, used for the batch's first frame; `size - 1` more are built.
    FrameBatch(const Scenario& scenario, FrameRenderer& first, int size);
    int size() const { return static_cast<int>(others_.size()) + 1; }
    /// Renders these frames (at most size()) and, when the scenario asks, their waveforms. A frame
    /// that fails is reported in its RenderedFrame; `fail_at_frame` throws in that one's render
    /// (for testing).
    std::vector<RenderedFrame> render(const std::vector<int>& frames, int fail_at_frame);

private:
    const Scenario& scenario_;
    FrameRenderer& first_;
    std::vector<std::unique_ptr<FrameRenderer>> others_;
};

}  // namespace ladarsim::sensor_model
