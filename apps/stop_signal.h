#pragma once
// Ctrl-C and SIGTERM as a request to stop: `render` finishes the frame it is on, `view` stops serving.
#include <atomic>

namespace ladarsim::apps {

/// Set by SIGINT/SIGTERM: the render loop stops after the frame it is on.
extern std::atomic<bool> g_stop;
/// The handler to install with std::signal: sets g_stop.
extern "C" void request_stop(int);

}  // namespace ladarsim::apps
