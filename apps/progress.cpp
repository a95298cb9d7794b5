#include "progress.h"

#include <unistd.h>

#include <cstdio>
#include <memory>

namespace ladarsim::apps {

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

std::function<void(int, int)> progress_lines(std::string what) {
    if (stderr_is_terminal()) {
        return [what](int done, int total) {
            std::fprintf(stderr, "\r%s %d/%d", what.c_str(), done, total);
            if (done == total) std::fprintf(stderr, "\n");
        };
    }
    auto last_tenth = std::make_shared<int>(-1);
    return [what, last_tenth](int done, int total) {
        const int tenth = total > 0 ? 10 * done / total : 10;
        if (tenth == *last_tenth && done != total) return;
        *last_tenth = tenth;
        std::fprintf(stderr, "%s %d/%d\n", what.c_str(), done, total);
    };
}

}  // namespace ladarsim::apps
