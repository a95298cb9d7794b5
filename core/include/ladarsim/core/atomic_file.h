#pragma once
// Every output file appears complete or not at all: it is written under `<name>.tmp` in the
// same directory (so the final rename stays within one file system and is atomic) and renamed
// only when everything has been written. A reader of a dataset, or a run interrupted half-way,
// therefore never sees a half-written frame.
#include <filesystem>
#include <fstream>

namespace ladarsim {

class AtomicFile {
public:
    /// Creates (or truncates) `<final_path>.tmp` for binary writing. Throws std::runtime_error
    /// naming the temporary if it cannot be created.
    explicit AtomicFile(std::filesystem::path final_path);
    /// Removes the temporary unless commit() succeeded: an exception thrown while writing
    /// leaves neither a partial file nor a stray temporary behind.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ofstream& stream() { return stream_; }
    const std::filesystem::path& temporary_path() const { return temporary_path_; }

    /// Flushes, closes and renames the temporary over the final path (replacing any previous
    /// file there). Throws std::runtime_error "<final_path>: cannot write: <the system's reason>"
    /// ("No space left on device") if any write failed; the temporary is then removed.
    void commit();

private:
    std::filesystem::path final_path_;
    std::filesystem::path temporary_path_;
    std::ofstream stream_;
    bool committed_ = false;
};

}  // namespace ladarsim
