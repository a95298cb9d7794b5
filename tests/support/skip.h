#pragma once
// A test that cannot run here (its shared data is missing) says why and is reported as skipped:
// test_main.cpp then exits 77, which ctest shows as "Skipped" (SKIP_RETURN_CODE), never as passed.
#include <source_location>
#include <sstream>
#include <string>

namespace ladarsim::test {

// Records that the running test case skipped, and why and where (a warning in its output).
// Defined in tests/test_main.cpp.
void skip(const std::string& why, std::source_location where = std::source_location::current());

}  // namespace ladarsim::test

// Skips the rest of the test case: LADARSIM_SKIP("shared data not present: " << file);
#define LADARSIM_SKIP(why)                                       \
    do {                                                         \
        std::ostringstream ladarsim_skip_why;                    \
        ladarsim_skip_why << why;                                \
        ::ladarsim::test::skip(ladarsim_skip_why.str());         \
        return;                                                  \
    } while (false)
