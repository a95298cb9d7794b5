#include "frame_writer.h"

#include <algorithm>
#include <cstdint>

#include "ladarsim/core/json_file.h"

namespace ladarsim::sensor_model {

namespace {

/// Writes a rendered frame into the staging directory: its PCD, EXR, ground truth and waveforms
/// (if given), then its record (last: its presence says the frame is complete). `render_s`: the
/// seconds its render took.
FrameRecord write_frame(const Frame& frame, double render_s, const std::optional<FrameWaveforms>& waveforms, const StagingFiles& files) {
    const int k = static_cast<int>(frame.index);
    const std::string stem = frame_file_stem(frame.index);
    write_frame_pcd(files.frames_dir / (stem + ".pcd"), frame);
    write_frame_exr(files.frames_dir / (stem + ".exr"), frame);
    if (waveforms) {
        std::filesystem::create_directories(files.waveforms_dir);
        write_waveforms_h5(files.waveforms_dir / (stem + ".h5"), *waveforms);
    }
    FrameRecord written{{}, ground_truth_of(frame)};
    write_ground_truth_json(files.truth_of(k), {written.truth});
    std::map<std::uint32_t, std::uint64_t> counts;
    for (const auto& r : frame.returns) ++counts[r.object_id];
    nlohmann::json by_object = nlohmann::json::object();
    for (const auto& [id, count] : counts) by_object[std::to_string(id)] = count;
    written.record = {{"index", frame.index},
                      {"start_time_s", frame.start_time_s},
                      {"end_time_s", frame.end_time_s},
                      {"gimbal_az_rad", frame.gimbal_az_rad},
                      {"gimbal_el_rad", frame.gimbal_el_rad},
                      {"returns", frame.returns.size()},
                      {"returns_by_object", by_object},
                      {"render_s", render_s}};
    write_json(files.record_of(k), written.record);
    return written;
}

}  // namespace

FrameWriter::FrameWriter(const StagingFiles& files, std::size_t in_flight)
    : files_(files), in_flight_(std::max<std::size_t>(1, in_flight)) {}

FrameWriter::~FrameWriter() { writing_.wait(); }

std::string FrameWriter::write(Frame frame, double render_s, std::optional<FrameWaveforms> waveforms) {
    std::string failure;
    if (pending_.size() == in_flight_) failure = finish();
    if (!failure.empty()) return failure;
    Pending& p = *pending_.emplace_back(std::make_unique<Pending>(Pending{std::move(frame), render_s, std::move(waveforms), {}, {}}));
    writing_.run([this, &p] {
        try {
            p.written = write_frame(p.frame, p.render_s, p.waveforms, files_);
        } catch (const std::exception& e) {
            p.failure = "frame " + std::to_string(p.frame.index) + ": " + e.what();
        }
    });
    return {};
}

std::string FrameWriter::finish() {
    writing_.wait();
    std::string failure;
    for (const auto& p : pending_) {
        if (failure.empty()) failure = p->failure;
        if (p->failure.empty()) written_.emplace(static_cast<int>(p->frame.index), std::move(p->written));
    }
    pending_.clear();
    return failure;
}

}  // namespace ladarsim::sensor_model
