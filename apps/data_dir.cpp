#include "data_dir.h"

#include "ladarsim/core/input_error.h"

namespace ladarsim::apps {

namespace fs = std::filesystem;

fs::path data_dir() {
    // The executable itself, wherever it was copied or moved (symbolic links to it followed). Without
    // /proc the path is left relative, and data_file's error names it.
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return (exe.parent_path() / ".." / "share" / "ladarsim").lexically_normal();
}

fs::path data_file(const fs::path& relative) {
    const fs::path file = data_dir() / relative;
    if (!fs::exists(file))
        throw InputError(file.string(), relative.filename().string(),
                         "missing from ladarsim's data, which lies beside the program in ../share/ladarsim "
                         "(build it, or install it with cmake --install)");
    return file;
}

}  // namespace ladarsim::apps
