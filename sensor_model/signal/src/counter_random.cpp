#include "ladarsim/sensor_model/signal/counter_random.h"

#include <cmath>
#include <numbers>

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

double RandomSequence::uniform() {
    if (used_ == 4) {
        buffer_ = uniform4(seed_, stream_, frame_, beam_, block_++);
        used_ = 0;
    }
    return buffer_[static_cast<std::size_t>(used_++)];
}

double RandomSequence::normal() {
    // Box-Muller gives two independent normals from two uniforms: the second is kept for the next
    // call (a beam draws several: speckle, detector noise and range jitter, a waveform's spectrum).
    if (spare_) {
        const double z = *spare_;
        spare_.reset();
        return z;
    }
    const double u1 = uniform(), u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1)), angle = 2.0 * std::numbers::pi * u2;
    spare_ = r * std::sin(angle);
    return r * std::cos(angle);
}

double RandomSequence::gamma_unit_mean(double k) {
    if (k < 1.0) {
        // Boost to k + 1, then scale by U^(1/k) (Marsaglia and Tsang, section 6).
        const double g = gamma_unit_mean(k + 1.0) * (k + 1.0);
        return g * std::pow(uniform(), 1.0 / k) / k;
    }
    const double d = k - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
    for (;;) {
        double x, v;
        do {
            x = normal();
            v = 1.0 + c * x;
        } while (v <= 0.0);
        v = v * v * v;
        const double u = uniform();
        if (u < 1.0 - 0.0331 * x * x * x * x || std::log(u) < 0.5 * x * x + d * (1.0 - v + std::log(v)))
            return d * v / k;
    }
}

int RandomSequence::poisson(double mean, double exp_minus_mean) {
    const double u = uniform();
    double p = exp_minus_mean, cumulative = p;
    int n = 0;
    while (u > cumulative && n < 10'000) {
        ++n;
        p *= mean / n;
        cumulative += p;
    }
    return n;
}

}  // namespace ladarsim::sensor_model
