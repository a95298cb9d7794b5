#pragma once
// `ladarsim view`: serves a rendered run and the browser viewer (apps/viewer/) on the loopback
// interface only.
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>

namespace ladarsim::apps {

struct ViewerOptions {
    std::filesystem::path run_dir;     ///< a dataset: manifest.json, frames/, ground_truth.json, ...
    std::filesystem::path viewer_dir;  ///< index.html, viewer.js, node_modules/three
    int port = 0;                      ///< 0: a free port
};

/// Binds 127.0.0.1, calls `ready` with the page's URL, then serves until `stop` reads true:
///   /                  the viewer page;  /viewer/<file> its scripts;  /three/<file> three.js
///   /run/<file>        any file inside the run directory (nothing outside it, nothing hidden)
///   /range/<frame>     a frame's range image from its EXR: width, height (uint32) and floats
///   /files             the run directory's top-level file names (JSON), to find detections
/// Throws InputError when the run directory has no manifest.json or the port cannot be bound.
void serve_viewer(const ViewerOptions& options, const std::function<void(const std::string& url)>& ready,
                  const std::atomic<bool>& stop);

/// The file a request path names under `root`, or empty when it would leave `root` (.., symbolic
/// links out of it, absolute paths, hidden files).
std::filesystem::path resolve_inside(const std::filesystem::path& root, const std::string& request_path);

}  // namespace ladarsim::apps
