#pragma once
// Progress on stderr: one updating line on a terminal; on anything else (a CI log, `tee`) a whole
// line now and then, never a carriage return.
#include <functional>
#include <string>

namespace ladarsim::apps {

/// Whether stderr is a terminal.
bool stderr_is_terminal();

/// A progress callback (done, total) printing "<what> done/total" and, from the second call on, the
/// time left at the pace so far (", about 3 min left"): on a terminal one line updated
/// in place and ended at the last; elsewhere a whole line at the first, at each further tenth of
/// the total and at the last.
std::function<void(int, int)> progress_lines(std::string what);

}  // namespace ladarsim::apps
