#pragma once
// Ctrl-C and SIGTERM as a request to stop: `render` finishes the frame it is on, `view` stops serving.
#include <atomic>
#include <string>

namespace ladarsim::apps {

/// Set by SIGINT/SIGTERM: the render loop stops after the frame it is on.
extern std::atomic<bool> g_stop;
/// The handler to install with std::signal: sets g_stop.
extern "C" void request_stop(int);

/// From now on, a stop not acknowledged (acknowledge_stop) within a second of the signal ends the
/// process with exit code 130 after printing `message` on stderr: a frame that takes long, or
/// preparation that looks at no flag, never makes Ctrl-C wait. The files written so far are
/// complete (each appears by an atomic rename), so nothing is lost but the frame in progress.
void stop_within_a_second(const std::string& message);
/// The stop was seen and the program is ending on its own: the deadline is off.
void acknowledge_stop();

}  // namespace ladarsim::apps
