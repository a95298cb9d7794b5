#pragma once
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::sensor_model {

/// The processes sharing one render (MPI ranks): each renders the frames k = rank, rank + size,
/// ... One process by default; apps/ provides the MPI one, so this library needs no MPI.
class FrameTeam {
public:
    virtual ~FrameTeam() = default;
    virtual int rank() const { return 0; }
    virtual int size() const { return 1; }
    /// Collective (every process calls it in step): true on all when any passes true.
    virtual bool any(bool mine) { return mine; }
};

/// The most frames one render may have, a scenario's render.frames and --frames alike: the
/// frames' bookkeeping (each one's gimbal pointing, manifest record) is held in memory.
inline constexpr int kMaxFrames = 10'000'000;

struct DatasetOptions {
    std::filesystem::path out_dir;
    std::optional<int> frames;          ///< overrides the scenario's render.frames; 1 to kMaxFrames
    std::optional<std::uint64_t> seed;  ///< overrides the scenario's render.seed
    int threads = 0;                    ///< 0 = all cores
    /// Called after each frame is on disk.
    std::function<void(int frames_done, int frames_total)> progress;
    /// Checked before each frame: when it reads true the run stops, leaving `<out_dir>.partial`
    /// with every finished frame and its record, which `resume` continues from.
    const std::atomic<bool>* stop = nullptr;
    /// Continue the interrupted run in `<out_dir>.partial` (same scenario, seed and frame count)
    /// instead of starting over; without one, start over.
    bool resume = false;
    /// Shares the frames among processes; null: this process renders them all.
    FrameTeam* team = nullptr;
    /// For testing failure handling: the frame whose rendering throws (none when negative).
    int fail_at_frame = -1;
};

/// A frame that could not be rendered or written, on this process or another of its team.
class FrameFailure : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct DatasetSummary {
    int frames = 0;
    std::uint64_t returns = 0;
    std::map<std::uint32_t, std::uint64_t> returns_by_object;  ///< object id -> returns over all frames
    double render_seconds = 0.0;
    double beams_per_second = 0.0;
    std::size_t background_points = 0;  ///< points of background.pcd (0: nothing static in view)
    bool interrupted = false;           ///< stopped early; `frames` were finished
    std::filesystem::path out_dir;
    std::vector<std::string> kept;      ///< the user's entries of an earlier dataset in out_dir, kept
};

/// Renders every frame of a scenario and writes the dataset:
///   frames/NNNNNN.pcd, frames/NNNNNN.exr, ground_truth.json, manifest.json, and background.pcd:
///   the static scene alone, noise-free, from each gimbal pointing used (the initial map that
///   detection subtracts), always written: 0 points when nothing static is in view
/// Each file is written under a temporary name and renamed when complete, inside `<out_dir>.partial`,
/// whose entries replace ladarsim's own in `out_dir` once every file is there (dataset_directory.h):
/// the user's files beside an earlier dataset are kept. `out_dir` may be absent, empty or an earlier
/// dataset; any other existing path is an InputError, checked before rendering starts.
/// A finished frame leaves a record beside its files (frames/NNNNNN.log.json and .truth.json),
/// which is how a resumed run, or the first process of a team, knows it is done; the records are
/// merged into ground_truth.json and manifest.json at the end. With a team, the first process
/// (rank 0) writes those and the initial map once every process has finished; the others return
/// a summary of their own frames. A failed frame throws FrameFailure on every process, after the
/// others have stopped at their current frame.
DatasetSummary render_dataset(Scenario scenario, const DatasetOptions& options);

}  // namespace ladarsim::sensor_model
