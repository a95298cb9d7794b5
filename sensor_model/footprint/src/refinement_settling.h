#pragma once
// Whether a refinement's cells have settled what the receiver will report, and which cells to
// split where they have not.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "footprint_context.h"
#include "refinement_region.h"

namespace ladarsim::sensor_model {

/// One judgement of a region's cells (one per thread, reused: its lists allocate nothing once
/// warm). The returns as they stand are the echoes grouped into surfaces, and surfaces the receiver
/// cannot tell apart into one return; cells that disagree with a neighbour (or with a witness
/// inside them) may hold a part of what the other found, each a draw of about half its cell's
/// energy either way. Settled when every return's energy is known to the tolerance of itself, or
/// of its pulse's threshold when weaker (below it, errors decide nothing).
class SettlingPass {
public:
    /// Whether the returns are settled; if not, marks the cells to split (Node::urgent, want).
    /// `echoes`: the beam's echoes as they stand (the region's leaves', keyed by Node number, and
    /// earlier stages'), scratch; `volumes`: its media's returns.
    bool settled(const FootprintContext& context, RefinementRegion& r, std::span<const Probe* const> witnesses,
                 std::vector<SurfaceEcho>& echoes, const std::vector<BeamSurface>& volumes);

private:
    /// Surfaces whose echoes overlap in range, or come closer than the pulse's length, make one
    /// pulse in the waveform: a cell shared by two of them changes nothing the receiver reports,
    /// so they are judged as one return (a cluster).
    void group_returns(std::vector<SurfaceEcho>& echoes);
    /// Each return's energy and range spread (so the energy at which its pulse reaches the
    /// threshold), its echoes taken in range order of their surfaces.
    void weigh_returns();
    /// Clears the cells' marks and tells each leaf which return its surface echo went to.
    void mark_leaves(RefinementRegion& r, const std::vector<SurfaceEcho>& echoes);
    void compare_neighbours(RefinementRegion& r);
    /// A witness that met something its cell's sub-ray did not (an edge's sliver between
    /// sub-rays) makes that cell uncertain by the witness's echo.
    void compare_witnesses(RefinementRegion& r, std::span<const Probe* const> witnesses, const std::vector<SurfaceEcho>& echoes);
    /// Marks the cells bounding an unsettled return (or an unseen witness's) urgent; false while
    /// any of them can still split.
    bool decide(RefinementRegion& r);

    void add_uncertainty(RefinementRegion::Node& n, std::int32_t g, double energy_j);
    /// Cell `a` may hold the other's surface (and media), and its own may be the other's.
    void involve(const RefinementRegion& r, RefinementRegion::Node& a, const Seen& other, std::int32_t other_surface,
                 std::uint32_t other_volume_first, std::uint32_t other_volume_count);
    std::int32_t volume_return(std::uint32_t object_id) const;
    template <class F> void each_echo(F&& f) const;

    const FootprintContext* context_ = nullptr;
    const std::vector<BeamSurface>* volumes_ = nullptr;
    double gap_ = 0.0;
    std::vector<std::uint32_t> surface_of_echo_;
    std::vector<BeamSurface> surfaces_;
    std::vector<std::pair<double, double>> extent_;
    std::vector<std::uint32_t> order_, merged_;
    std::size_t clusters_ = 0, returns_ = 0;
    std::vector<double> energy_, variance_, threshold_, mean_, spread_;
    std::vector<std::uint8_t> unsettled_, undecided_;
    std::vector<int> samples_of_;
};

}  // namespace ladarsim::sensor_model
