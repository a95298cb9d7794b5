#pragma once
// The line the importers print once a capture is written as a dataset.
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/frame.h"

namespace ladarsim::apps {

inline void print_import_summary(const std::vector<Frame>& frames, const std::string& source, const std::string& out_dir,
                                 const std::vector<std::string>& kept) {
    std::size_t returns = 0;
    for (const auto& f : frames) returns += f.returns.size();
    std::printf("decoded %zu frames, %zu returns from %s into %s/frames\n", frames.size(), returns, source.c_str(), out_dir.c_str());
    if (!kept.empty()) std::printf("%s\n", kept_files_note(kept, out_dir).c_str());
}

}  // namespace ladarsim::apps
