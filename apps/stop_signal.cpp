#include "stop_signal.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <csignal>

namespace ladarsim::apps {

namespace {

// Set before the signal can arrive, read only by the handlers: async-signal-safe.
std::array<char, 4096> g_deadline_message{};
std::size_t g_deadline_message_size = 0;
volatile std::sig_atomic_t g_deadline_armed = 0;

extern "C" void stop_now(int) {
    (void)!::write(STDERR_FILENO, g_deadline_message.data(), g_deadline_message_size);
    ::_exit(130);
}

}  // namespace

std::atomic<bool> g_stop{false};

extern "C" void request_stop(int) {
    g_stop.store(true);
    if (g_deadline_armed) ::alarm(1);
}

void stop_within_a_second(const std::string& message) {
    g_deadline_message_size = std::min(message.size(), g_deadline_message.size());
    std::copy_n(message.begin(), g_deadline_message_size, g_deadline_message.begin());
    std::signal(SIGALRM, stop_now);
    g_deadline_armed = 1;
}

void acknowledge_stop() {
    g_deadline_armed = 0;
    ::alarm(0);
}

}  // namespace ladarsim::apps
