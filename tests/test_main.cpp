// The test programs' main: Catch2's, except that a run in which a test case skipped (its shared
// data is missing, support/skip.h) and none failed exits LADARSIM_SKIP_RETURN_CODE, the code
// ctest reports as skipped (tests/CMakeLists.txt).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "support/skip.h"

namespace {

std::vector<std::pair<std::string, std::string>>& skipped() {
    static std::vector<std::pair<std::string, std::string>> tests;  // test case, why
    return tests;
}

}  // namespace

void ladarsim::test::skip(const std::string& why, std::source_location where) {
    WARN("skipped at " << where.file_name() << ':' << where.line() << ": " << why);
    skipped().emplace_back(Catch::getResultCapture().getCurrentTestName(), why);
}

int main(int argc, char* argv[]) {
    const int result = Catch::Session().run(argc, argv);
    for (const auto& [test, why] : skipped()) std::cerr << "skipped: " << test << ": " << why << '\n';
    return result == 0 && !skipped().empty() ? LADARSIM_SKIP_RETURN_CODE : result;
}
