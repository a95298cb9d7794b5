#include "frames_at_once.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace ladarsim::sensor_model {

int frames_at_once(int threads, int frames) { return std::clamp(threads / 4, 1, std::max(1, frames)); }

FrameBatch::FrameBatch(const Scenario& scenario, FrameRenderer& first, int size)
    : scenario_(scenario), first_(first), others_(static_cast<std::size_t>(std::max(1, size) - 1)) {
    tbb::parallel_for(std::size_t{0}, others_.size(), [&](std::size_t i) { others_[i] = std::make_unique<FrameRenderer>(scenario); });
}

std::vector<RenderedFrame> FrameBatch::render(const std::vector<int>& frames, int fail_at_frame) {
    if (frames.size() > static_cast<std::size_t>(size())) throw std::logic_error("FrameBatch: more frames than renderers");
    std::vector<RenderedFrame> rendered(frames.size());
    const auto batch_started = std::chrono::steady_clock::now();
    tbb::parallel_for(std::size_t{0}, frames.size(), [&](std::size_t i) {
        FrameRenderer& renderer = i == 0 ? first_ : *others_[i - 1];
        RenderedFrame& r = rendered[i];
        const int k = frames[i];
        try {
            if (k == fail_at_frame) throw std::runtime_error("failure injected for testing");
            const auto started = std::chrono::steady_clock::now();
            r.frame = renderer.render(static_cast<std::uint64_t>(k));
            r.render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            if (scenario_.render.waveforms) r.waveforms = renderer.take_waveforms();
        } catch (const std::exception& e) {
            r.failure = "frame " + std::to_string(k) + ": " + e.what();
        }
    });
    if (rendered.size() > 1) {
        const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - batch_started).count();
        double own_s = 0.0;
        for (const RenderedFrame& r : rendered) own_s += r.render_s;
        if (own_s > 0.0)
            for (RenderedFrame& r : rendered) r.render_s *= wall_s / own_s;
    }
    return rendered;
}

}  // namespace ladarsim::sensor_model
