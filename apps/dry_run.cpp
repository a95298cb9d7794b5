#include "dry_run.h"

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/exr_file.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/geometry_checks.h"

namespace ladarsim::apps {

namespace {

std::string duration_text(double seconds) {
    char text[64];
    if (seconds < 1.0) std::snprintf(text, sizeof text, "%.0f ms", seconds * 1e3);
    else if (seconds < 90.0) std::snprintf(text, sizeof text, "%.1f s", seconds);
    else if (seconds < 5400.0) std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
    else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
    return text;
}

std::string size_text(double bytes) {
    char text[64];
    if (bytes < 1e6) std::snprintf(text, sizeof text, "%.0f kB", bytes / 1e3);
    else if (bytes < 1e9) std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
    else std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
    return text;
}

}  // namespace

void print_dry_run(const sensor_model::Scenario& scenario, int threads, const std::filesystem::path& out_dir) {
    const std::filesystem::path out = checked_dataset_dir(out_dir);
    const int workers = threads > 0 ? threads : tbb::info::default_concurrency();
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(workers));
    sensor_model::FrameRenderer renderer(scenario);
    const int frames = scenario.render.frames;
    for (const std::string& w : sensor_model::geometry_warnings(scenario, renderer, frames))
        spdlog::warn("{}: {}", scenario.file.string(), w);

    const std::filesystem::path scratch = std::filesystem::temp_directory_path() / ("ladarsim-dry-run-" + std::to_string(::getpid()));
    std::filesystem::create_directories(scratch);
    double seconds = 0.0, bytes = 0.0;
    const std::set<int> samples{0, frames / 2, frames - 1};
    try {
        for (const int k : samples) {
            const auto started = std::chrono::steady_clock::now();
            const Frame frame = renderer.render(static_cast<std::uint64_t>(k));
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            write_frame_pcd(scratch / "frame.pcd", frame);
            write_frame_exr(scratch / "frame.exr", frame);
            bytes += static_cast<double>(std::filesystem::file_size(scratch / "frame.pcd") + std::filesystem::file_size(scratch / "frame.exr"));
        }
    } catch (...) {
        std::filesystem::remove_all(scratch);
        throw;
    }
    std::filesystem::remove_all(scratch);
    const double per_frame_s = seconds / samples.size(), per_frame_bytes = bytes / samples.size();
    const auto beams = static_cast<std::uint64_t>(renderer.raster().beam_count());
    std::printf("dry run of %s (nothing written): %d frames of %llu beams, %llu beams in all\n", scenario.file.string().c_str(),
                frames, static_cast<unsigned long long>(beams), static_cast<unsigned long long>(beams) * frames);
    std::printf("  about %s to render on %d threads and %s on disk (from frames",
                duration_text(per_frame_s * frames).c_str(), workers, size_text(per_frame_bytes * frames).c_str());
    for (const int k : samples) std::printf(" %d", k);
    std::printf(": %s and %s a frame)\n  into %s\n", duration_text(per_frame_s).c_str(), size_text(per_frame_bytes).c_str(),
                out.string().c_str());
}

}  // namespace ladarsim::apps
