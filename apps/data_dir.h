#pragma once
// Where the program's run-time data lies (the plot scripts, the viewer's web files, the bundled
// scenarios and models): beside the executable, in <exe_dir>/../share/ladarsim. `cmake --install`
// puts bin/ladarsim and share/ladarsim/ there; the build tree mirrors it (build/apps/ladarsim,
// build/share/ladarsim), so a built or installed program never needs its source tree.
#include <filesystem>

namespace ladarsim::apps {

/// <directory of this executable>/../share/ladarsim (not checked).
std::filesystem::path data_dir();

/// data_dir() / relative; throws InputError naming the path when it is missing.
std::filesystem::path data_file(const std::filesystem::path& relative);

}  // namespace ladarsim::apps
