#pragma once
// Counter-based random numbers: every draw is a pure function of (seed, frame, beam, sample),
// so results do not depend on thread count or on the order in which beams are processed.
#include <array>
#include <cstdint>

namespace ladarsim::sensor_model {

/// Which physical process a draw belongs to, so that two processes never share a stream.
enum class RandomStream : std::uint32_t { footprint_jitter = 1 };

/// Four independent uniform numbers in (0, 1] for one (stream, frame, beam, sample).
std::array<double, 4> uniform4(std::uint64_t seed, RandomStream stream, std::uint64_t frame,
                               std::uint32_t beam, std::uint32_t sample);

}  // namespace ladarsim::sensor_model
