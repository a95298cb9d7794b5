// frame_file_stem: six-digit, zero-padded names that sort in frame order.
#include <catch2/catch.hpp>

#include "ladarsim/dataset/frame_io.h"

using ladarsim::frame_file_stem;

TEST_CASE("frame file stems are six digits, zero-padded", "[frame_io]") {
    CHECK(frame_file_stem(0) == "000000");
    CHECK(frame_file_stem(42) == "000042");
    CHECK(frame_file_stem(999999) == "999999");
    CHECK(frame_file_stem(1234567) == "1234567");  // more frames than six digits: nothing is cut off
}
