// AtomicFile: a file appears complete under its final name or not at all.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "ladarsim/core/atomic_file.h"
#include "../support/scratch_dir.h"

using ladarsim::AtomicFile;
using ladarsim::test::ScratchDir;

namespace {
std::string contents(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("commit: the final file holds everything written and no temporary is left", "[atomic_file]") {
    const ScratchDir dir;
    const auto path = dir / "out.txt";
    {
        AtomicFile out(path);
        CHECK(out.temporary_path() == dir / "out.txt.tmp");
        out.stream() << "complete";
        CHECK(std::filesystem::exists(dir / "out.txt.tmp"));
        CHECK_FALSE(std::filesystem::exists(path));  // nothing under the final name until commit
        out.commit();
    }
    CHECK(contents(path) == "complete");
    CHECK_FALSE(std::filesystem::exists(dir / "out.txt.tmp"));
}

TEST_CASE("commit replaces an existing file", "[atomic_file]") {
    const ScratchDir dir;
    const auto path = dir / "out.txt";
    std::ofstream(path) << "old";
    AtomicFile out(path);
    out.stream() << "new";
    out.commit();
    CHECK(contents(path) == "new");
}

TEST_CASE("an exception while writing leaves the old file and no temporary", "[atomic_file]") {
    const ScratchDir dir;
    const auto path = dir / "out.txt";
    std::ofstream(path) << "old";
    CHECK_THROWS_AS(
        [&] {
            AtomicFile out(path);
            out.stream() << "half a fi";
            throw std::runtime_error("renderer failed");
        }(),
        std::runtime_error);
    CHECK(contents(path) == "old");
    CHECK_FALSE(std::filesystem::exists(dir / "out.txt.tmp"));
}

TEST_CASE("a directory that does not exist: runtime_error naming the temporary", "[atomic_file]") {
    const ScratchDir dir;
    const auto path = dir / "missing" / "out.txt";
    try {
        AtomicFile out(path);
        FAIL("no exception");
    } catch (const std::runtime_error& e) {
        CHECK_THAT(e.what(), Catch::Contains((dir / "missing" / "out.txt.tmp").string()));
    }
    CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("a full disk: runtime_error naming the file and the system's reason", "[atomic_file]") {
    const ScratchDir dir;
    const auto path = dir / "out.bin";
    // The temporary is opened through a link to /dev/full, where every write fails with ENOSPC.
    std::filesystem::create_symlink("/dev/full", dir / "out.bin.tmp");
    try {
        AtomicFile out(path);
        out.stream() << std::string(1 << 20, 'x');
        out.commit();
        FAIL("no exception");
    } catch (const std::runtime_error& e) {
        CHECK_THAT(e.what(), Catch::Contains(path.string() + ": cannot write: No space left on device"));
    }
    CHECK_FALSE(std::filesystem::exists(path));
}
