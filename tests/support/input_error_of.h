#pragma once
// The InputError a reader throws, for a test to check the file, field and problem it names.
#include <stdexcept>

#include "ladarsim/core/input_error.h"

namespace ladarsim::test {

/// Calls `read` and returns the InputError it throws; throws std::logic_error, failing the test,
/// when it throws none.
template <typename Read>
InputError input_error_of(Read&& read) {
    try {
        read();
    } catch (const InputError& e) {
        return e;
    }
    throw std::logic_error("no InputError thrown");
}

}  // namespace ladarsim::test
