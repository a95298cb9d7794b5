#include "stop_signal.h"

namespace ladarsim::apps {

std::atomic<bool> g_stop{false};
extern "C" void request_stop(int) { g_stop.store(true); }

}  // namespace ladarsim::apps
