#include "ladarsim/sensor_model/counter_random.h"

#include <Random123/philox.h>
#include <Random123/uniform.hpp>

namespace ladarsim::sensor_model {

std::array<double, 4> uniform4(std::uint64_t seed, RandomStream stream, std::uint64_t frame,
                               std::uint32_t beam, std::uint32_t sample) {
    using Philox = r123::Philox4x32;
    const Philox::key_type key = {{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
    const Philox::ctr_type counter = {{static_cast<std::uint32_t>(frame), static_cast<std::uint32_t>(frame >> 32) ^
                                                                               (static_cast<std::uint32_t>(stream) << 24),
                                       beam, sample}};
    const Philox::ctr_type bits = Philox{}(counter, key);
    return {r123::u01<double>(bits[0]), r123::u01<double>(bits[1]), r123::u01<double>(bits[2]),
            r123::u01<double>(bits[3])};
}

}  // namespace ladarsim::sensor_model
