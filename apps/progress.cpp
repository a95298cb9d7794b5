#include "progress.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

namespace ladarsim::apps {

namespace {

using Clock = std::chrono::steady_clock;

/// ", about 3 min left" from the pace since the first call (a resumed run's first call already
/// counts the frames it found done), or "" before there is a pace or once done.
class TimeLeft {
public:
    std::string operator()(int done, int total) {
        const auto now = Clock::now();
        if (first_done_ < 0) {
            first_done_ = done;
            first_time_ = now;
            return "";
        }
        if (done <= first_done_ || done >= total) return "";
        const double seconds_each = std::chrono::duration<double>(now - first_time_).count() / (done - first_done_);
        const double left_s = seconds_each * (total - done);
        char text[64];
        if (left_s < 90.0) std::snprintf(text, sizeof text, ", about %.0f s left", std::ceil(left_s));
        else if (left_s < 5400.0) std::snprintf(text, sizeof text, ", about %.0f min left", std::round(left_s / 60.0));
        else std::snprintf(text, sizeof text, ", about %.0f h %.0f min left", std::floor(left_s / 3600.0),
                           std::floor(std::fmod(left_s, 3600.0) / 60.0));
        return text;
    }

private:
    int first_done_ = -1;
    Clock::time_point first_time_;
};

}  // namespace

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

std::function<void(int, int)> progress_lines(std::string what) {
    auto time_left = std::make_shared<TimeLeft>();
    if (stderr_is_terminal()) {
        return [what, time_left](int done, int total) {
            // Cleared to the end of the line: the estimate's text shortens.
            std::fprintf(stderr, "\r%s %d/%d%s\033[K", what.c_str(), done, total, (*time_left)(done, total).c_str());
            if (done == total) std::fprintf(stderr, "\n");
        };
    }
    auto last_tenth = std::make_shared<int>(-1);
    return [what, last_tenth, time_left](int done, int total) {
        const std::string left = (*time_left)(done, total);
        const int tenth = total > 0 ? 10 * done / total : 10;
        if (tenth == *last_tenth && done != total) return;
        *last_tenth = tenth;
        std::fprintf(stderr, "%s %d/%d%s\n", what.c_str(), done, total, left.c_str());
    };
}

}  // namespace ladarsim::apps
