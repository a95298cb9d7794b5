#pragma once
// The cells of equal energy a footprint's part is refined in (CellRefinement).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "ladarsim/sensor_model/footprint/footprint.h"
#include "sub_ray_seen.h"

namespace ladarsim::sensor_model {

/// A refined region starts as base x base cells of equal energy (2 x 2 for a whole footprint, whose
/// probes already tell where its edges are; 4 x 4 for a target's outline); a cell splits in two
/// along an axis (or in four), up to 8 times along each (a whole footprint's sliver holding 0.1 %
/// of the beam is resolved), and a region traces at most so many sub-rays.
inline constexpr int kMaxSplits = 8;
inline constexpr std::size_t kFootprintSamples = 256;  ///< a whole footprint's (a recorded map's grazing one)
inline constexpr int kFootprintBase = 2;
inline constexpr int kOutlineBase = 4;
/// Random-draw numbers of the cells: every (splits along x, splits along y, i, j) its own.
constexpr std::uint32_t cells_along(int base, int splits) { return static_cast<std::uint32_t>(base) << splits; }
constexpr std::uint32_t first_cell_number(int base, int splits_x, int splits_y) {
    std::uint32_t n = 0;
    for (int a = 0; a <= kMaxSplits; ++a)
        for (int b = 0; b <= kMaxSplits; ++b) {
            if (a == splits_x && b == splits_y) return n;
            n += cells_along(base, a) * cells_along(base, b);
        }
    return n;
}

/// The key a leaf's echo carries among the beam's (SurfaceEcho::sample), so that the settling pass
/// finds the cell of each echo after they are sorted; earlier stages' echoes carry 0.
constexpr std::uint32_t leaf_key(std::size_t node) { return std::uint32_t{1} << 24 | static_cast<std::uint32_t>(node); }
/// The node a key names, or -1 for an echo that is not a leaf's.
constexpr std::int64_t node_of_key(std::uint32_t key) { return key >> 24 == 0 ? -1 : std::int64_t{key & 0xFFFFFFu}; }

/// One rectangle of offsets refined as a tree of cells of equal energy density, in the coordinates
/// of the two axis CDFs (a cell then carries the energy of its area): cells split where their
/// sub-rays disagree with their neighbours', along the axis across which they disagree, so that a
/// straight edge is followed by thin cells along it. A split cell's sub-ray is reused by the child
/// it falls in (with jitter).
struct RefinementRegion {
    FootprintRect rect{};
    std::optional<FootprintRect> excluded;  ///< accounted elsewhere: sub-rays there are dropped
    double share = 0.0;                     ///< > 0: the kept cells carry this share of the beam
    std::uint32_t first_sample = 0;         ///< where its random draws start
    double cdf_x0 = 0.0, cdf_dx = 0.0, cdf_y0 = 0.0, cdf_dy = 0.0;

    struct Node {
        double u0, u1, v0, v1;        ///< the cell, in the region's CDF square [0, 1)^2
        std::uint8_t splits_x, splits_y;
        std::uint32_t i, j;           ///< its index along each axis at those splits
        std::int32_t first_child = -1;
        std::uint8_t split = 0;       ///< how it was split: bit 0 along x, bit 1 along y
        std::uint8_t want = 0;        ///< the axes it should split along
        bool traced = false;
        bool kept = true;             ///< not in the excluded part
        bool boundary = false;
        bool urgent = false;          ///< bounds a return whose energy is not settled
        double u, v;                  ///< its sub-ray's place in the CDF square
        double x_rad, y_rad;
        double weight;                ///< the cell's share of the beam (0 beyond the truncation)
        Seen seen;
        std::uint32_t volume_first = 0, volume_count = 0;     ///< its echoes in `volume_echoes`
        std::array<std::int32_t, 4> touches{-1, -1, -1, -1};  ///< returns its cell may hold a part of
        std::int32_t surface = -1;    ///< the return its surface echo went to
        std::int32_t adopt = -1;      ///< a probe inside it that disagrees: in `probes`
        bool leaf() const { return first_child < 0; }
    };
    struct VolumeEcho {
        std::uint32_t object_id;
        double range_m;
        double energy_j;  ///< per unit of beam share
        double spread_m;  ///< of its free paths' ranges
    };
    /// A probe inside the region, as a sub-ray its cell can adopt (no ray needed) once split so
    /// that the probe and the cell's own sub-ray lie apart.
    struct AdoptedProbe {
        double u, v;
        Seen seen;
    };
    std::vector<Node> nodes;  ///< the base cells first, then children, four (or two) together
    std::vector<VolumeEcho> volume_echoes;
    std::vector<AdoptedProbe> probes;
    /// The witnesses' places in the CDF square and what they met, worked out once.
    std::vector<double> witness_u, witness_v;
    std::vector<Seen> witness_seen;
    bool media = false;       ///< sub-rays look into volume media (probes do not: never adopted)
    /// The region is an object's outline: its border is the object's edge somewhere along it, so a
    /// cell on the border whose sub-ray met the object may hold an edge of it.
    bool outline = false;
    int base = kFootprintBase;  ///< cells along each axis to start
    std::size_t max_samples = kFootprintSamples;
    double scale = 1.0;       ///< weights as carried: share / kept weight, or 1

    void reset(const Footprint& footprint, const FootprintRect& r, const std::optional<FootprintRect>& without, double share_of_beam,
               std::uint32_t first) {
        nodes.clear();
        volume_echoes.clear();
        probes.clear();
        witness_u.clear();
        witness_v.clear();
        witness_seen.clear();
        outline = false;
        base = kFootprintBase;
        max_samples = kFootprintSamples;
        rect = r;
        excluded = without;
        share = share_of_beam;
        first_sample = first;
        cdf_x0 = footprint.axis_cdf(r.x_lo);
        cdf_dx = footprint.axis_cdf(r.x_hi) - cdf_x0;
        cdf_y0 = footprint.axis_cdf(r.y_lo);
        cdf_dy = footprint.axis_cdf(r.y_hi) - cdf_y0;
    }
    std::uint32_t number(const Node& n) const {
        return first_sample + first_cell_number(base, n.splits_x, n.splits_y) + n.i * cells_along(base, n.splits_y) + n.j;
    }
    /// Fills a node's sub-ray at (u, v) and its weight.
    void place(const Footprint& footprint, Node& n, double u, double v) const {
        n.u = u;
        n.v = v;
        n.x_rad = footprint.axis_offset(cdf_x0 + u * cdf_dx);
        n.y_rad = footprint.axis_offset(cdf_y0 + v * cdf_dy);
        n.weight = footprint.within_truncation(n.x_rad, n.y_rad)
                       ? footprint.cell_weight(cdf_dx * (n.u1 - n.u0), cdf_dy * (n.v1 - n.v0))
                       : 0.0;
        n.kept = !excluded || !footprint.contains(*excluded, n.x_rad, n.y_rad);
    }
    /// The leaf holding CDF-square point (u, v), or null outside the square.
    const Node* leaf_at(double u, double v) const {
        if (!(u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0)) return nullptr;
        const Node* n = &nodes[static_cast<std::size_t>(std::min(static_cast<int>(u * base), base - 1) * base +
                                                        std::min(static_cast<int>(v * base), base - 1))];
        while (!n->leaf()) {
            const int a = (n->split & 1) && u >= 0.5 * (n->u0 + n->u1) ? 1 : 0;
            const int b = (n->split & 2) && v >= 0.5 * (n->v0 + n->v1) ? 1 : 0;
            n = &nodes[static_cast<std::size_t>(n->first_child + (n->split == 3 ? 2 * a + b : a + b))];
        }
        return n;
    }
};

}  // namespace ladarsim::sensor_model
