#include "ladarsim/core/atomic_file.h"

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
    // A stream that failed made no system call since (its writes stop at the first failure), so
    // errno still holds the system's reason; else closing flushes, and a failure there sets it.
    const bool failed_earlier = stream_.fail();
    int reason = failed_earlier ? errno : 0;
    if (!failed_earlier) errno = 0;
    stream_.close();
    if (!failed_earlier) reason = errno;
    if (stream_.fail()) {
        throw std::runtime_error(final_path_.string() + ": cannot write: " +
                                 (reason ? std::strerror(reason) : "the stream failed (no reason given by the system)"));
    }
    std::filesystem::rename(temporary_path_, final_path_);
    committed_ = true;
}

}  // namespace ladarsim
