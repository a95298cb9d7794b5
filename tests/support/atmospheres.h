#pragma once
#include <limits>

#include "ladarsim/sensor_model/signal/atmosphere.h"

namespace ladarsim::test {

/// No extinction at all: closed forms without the atmosphere's factor.
inline sensor_model::Atmosphere vacuum() {
    sensor_model::Atmosphere a;
    a.visibility_m = std::numeric_limits<double>::infinity();
    return a;
}

}  // namespace ladarsim::test
