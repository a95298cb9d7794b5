// Loading datasets for detection: clear errors for what is missing or malformed.
#include <catch2/catch.hpp>

#include <fstream>

#include "ladarsim/dataset/input_error.h"
#include "ladarsim/detect/sequence.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;

TEST_CASE("a missing, empty or malformed dataset is one InputError naming the file", "[detect]") {
    const test::ScratchDir dir;
    CHECK_THROWS_AS(detect::load_sequence(dir / "nowhere"), InputError);
    std::filesystem::create_directories(dir / "frames");
    try {
        detect::load_sequence(dir.path());
        FAIL("no error for a dataset without frames");
    } catch (const InputError& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("frames"));
    }
    std::ofstream(dir / "frames" / "000000.pcd") << "this is not a point cloud";
    try {
        detect::load_sequence(dir.path());
        FAIL("no error for a malformed frame");
    } catch (const InputError& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("000000.pcd"));
    }
}
