#pragma once
// One way of integrating (a part of) a beam's footprint; the integrator chooses among them for
// each beam (FootprintIntegrator::integrate).
#include <cstdint>
#include <optional>
#include <span>

#include "ladarsim/sensor_model/footprint/beam.h"
#include "ladarsim/sensor_model/footprint/footprint.h"

namespace ladarsim::sensor_model {

/// The beam being integrated, as every strategy sees it.
struct BeamSetting {
    const BeamAim& aim;
    /// Its own axis first, then its neighbours' axes and extra probes, sentinels among them.
    std::span<const Probe> probes;
    /// Probes (and seeds on targets) whose hits the sub-rays of their cells must agree with.
    std::span<const Probe* const> witnesses;
    bool media;           ///< its cone meets a volume medium (fog, cloud)
    std::uint64_t frame;  ///< keys its random draws, with the raster cell
    std::uint32_t lone_target_id = 0;  ///< with one small or moving object in its cone, that one
};

/// The part of a footprint a strategy is asked for.
struct FootprintPart {
    FootprintRect rect{};                    ///< footprint offsets it covers (the square, or a target's outline)
    std::optional<FootprintRect> excluded;   ///< inside `rect` but accounted for elsewhere
    double share = 1.0;                      ///< of the beam its echoes carry; 0: what its cells weigh
    std::uint32_t first_draw = 0;            ///< where its random draws start
};

/// What a strategy made of its part: integrated (its echoes appended), or why not.
enum class Outcome {
    integrated,
    empty,     ///< nothing there (no echo)
    declined,  ///< not this strategy's case (nothing appended)
    parted,    ///< declined: the probes are parted between something and nothing, or two objects
};

struct Integration {
    Outcome outcome;
    double share = 0.0;  ///< of the beam the appended echoes account for
};

class FootprintStrategy {
public:
    virtual ~FootprintStrategy() = default;
    /// Appends the echoes of `part` of the beam to `out` (and the rays it traced to `out.rays`).
    virtual Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const = 0;
};

}  // namespace ladarsim::sensor_model
