#include "ladarsim/dataset/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace ladarsim {

AtomicFile::AtomicFile(std::filesystem::path final_path)
    : final_path_(std::move(final_path)), temporary_path_(final_path_.string() + ".tmp") {
    stream_.open(temporary_path_, std::ios::binary | std::ios::trunc);
    if (!stream_) {
        throw std::runtime_error(temporary_path_.string() + ": cannot create: " + std::strerror(errno));
    }
}

AtomicFile::~AtomicFile() {
    if (committed_) return;
    stream_.close();
    std::error_code ignored;  // a destructor must not throw; the temporary may not even exist
    std::filesystem::remove(temporary_path_, ignored);
}

void AtomicFile::commit() {
    stream_.close();
    if (stream_.fail()) throw std::runtime_error(temporary_path_.string() + ": write failed");
    std::filesystem::rename(temporary_path_, final_path_);
    committed_ = true;
}

}  // namespace ladarsim
