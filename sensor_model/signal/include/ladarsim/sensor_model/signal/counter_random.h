#pragma once
// Counter-based random numbers: every draw is a pure function of (seed, frame, beam, sample),
// so results do not depend on thread count or on the order in which beams are processed.
#include <array>
#include <cstdint>
#include <optional>

namespace ladarsim::sensor_model {

/// Which physical process a draw belongs to, so that two processes never share a stream.
enum class RandomStream : std::uint32_t {
    footprint_jitter = 1,
    speckle = 2,
    detector_noise = 3,   ///< noise on closed-form returns
    waveform_noise = 4,   ///< noise samples of built waveforms
    false_alarms = 5,
    volume_scatter = 6,   ///< free paths inside fog and cloud
    // 7 and 8 were the shared sub-rays over a recorded map, before its footprints were integrated
    // along lines: left unused, so that no stream changes number.
    target_lattice_jitter = 9,  ///< a line's shared sub-rays over a target (TargetLattice)
};

/// Four independent uniform numbers in (0, 1] for one (stream, frame, beam, sample).
std::array<double, 4> uniform4(std::uint64_t seed, RandomStream stream, std::uint64_t frame,
                               std::uint32_t beam, std::uint32_t sample);

/// Draws for one (stream, frame, beam), in order: the k-th draw is the same whatever else runs,
/// on whichever thread. Each call of uniform4 yields four numbers; they are handed out one by one.
class RandomSequence {
public:
    RandomSequence(std::uint64_t seed, RandomStream stream, std::uint64_t frame, std::uint32_t beam,
                   std::uint32_t first_block = 0)
        : seed_(seed), stream_(stream), frame_(frame), beam_(beam), block_(first_block) {}

    double uniform();  ///< in (0, 1]
    double normal();   ///< standard normal (Box-Muller)
    /// Gamma distributed with shape k and mean 1 (Marsaglia and Tsang 2000): speckle of k cells.
    double gamma_unit_mean(double k);
    /// Poisson distributed with the given mean, exp(-mean) given (inversion; for the small means
    /// of false alarms, drawn for every beam with one mean).
    int poisson(double mean, double exp_minus_mean);

private:
    std::uint64_t seed_;
    RandomStream stream_;
    std::uint64_t frame_;
    std::uint32_t beam_;
    std::uint32_t block_;
    std::array<double, 4> buffer_{};
    int used_ = 4;
    std::optional<double> spare_;  ///< Box-Muller's second normal
};

}  // namespace ladarsim::sensor_model
