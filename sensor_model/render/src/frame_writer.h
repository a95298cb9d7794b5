#pragma once
// A render's frames written into its staging directory while the next ones render.
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/task_group.h>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/dataset/waveform_file.h"

namespace ladarsim::sensor_model {

/// The files of a render being staged beside its destination.
struct StagingFiles {
    std::filesystem::path staging, run_file, frames_dir, waveforms_dir;
    explicit StagingFiles(const std::filesystem::path& dir)
        : staging(dir), run_file(dir / "run.json"), frames_dir(dir / "frames"), waveforms_dir(dir / "waveforms") {}
    /// A finished frame's record (written last: its presence says the frame is complete) and ground truth.
    std::filesystem::path record_of(int k) const { return frames_dir / (frame_file_stem(static_cast<std::uint64_t>(k)) + ".log.json"); }
    std::filesystem::path truth_of(int k) const { return frames_dir / (frame_file_stem(static_cast<std::uint64_t>(k)) + ".truth.json"); }
};

/// What the dataset's manifest and ground truth take from a finished frame.
struct FrameRecord {
    nlohmann::json record;
    FrameGroundTruth truth;
};

/// Writes frames while the next ones render: encoding and writing a frame's files (zlib for the
/// EXR, the file system's own work) took a sixth of a run's time on one core, and while it ran
/// alone the other cores waited. Up to `in_flight` frames are written at once (one per thread:
/// one writer would be the bottleneck of many cores), which bounds the memory. A frame is
/// complete when its record is written, whatever the order, so an interruption leaves finished
/// frames that --resume keeps, as writing in line would.
class FrameWriter {
public:
    FrameWriter(const StagingFiles& files, std::size_t in_flight);
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;
    ~FrameWriter();
    /// Starts writing this frame (and its waveforms, when the scenario asks for them), once fewer
    /// than `in_flight` are being written. Returns the failure of a frame written before ("" if none).
    std::string write(Frame frame, double render_s, std::optional<FrameWaveforms> waveforms);
    /// Waits for the frames being written. Returns the first one's failure ("" if none).
    std::string finish();
    /// The records of the frames this writer finished, by frame index: the run's summary takes
    /// them from here rather than reading back what it wrote.
    std::map<int, FrameRecord>& written() { return written_; }

private:
    struct Pending {
        Frame frame;
        double render_s;
        std::optional<FrameWaveforms> waveforms;
        std::string failure;
        FrameRecord written;
    };
    const StagingFiles& files_;
    const std::size_t in_flight_;
    tbb::task_group writing_;
    std::vector<std::unique_ptr<Pending>> pending_;
    std::map<int, FrameRecord> written_;
};

}  // namespace ladarsim::sensor_model
