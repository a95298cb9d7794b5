#pragma once
// Sampling where nothing simpler holds: cells of equal energy that split where their sub-rays
// disagree, until what the receiver reports is settled.
#include <cstddef>

#include "footprint_context.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"
#include "recorded_map_sampling.h"
#include "refinement_region.h"
#include "straight_edge.h"

namespace ladarsim::sensor_model {

/// How a refinement starts.
struct RefinementPlan {
    int base = kFootprintBase;                    ///< cells along each axis to start
    std::size_t max_samples = kFootprintSamples;  ///< sub-rays it may trace
    /// The part is an object's outline: its border is the object's edge somewhere along it.
    bool outline = false;
};

/// Cells (base x base to start) split, along the axis across which they disagree, where
/// neighbouring sub-rays, or a witness and the sub-ray of its cell, disagree (another object,
/// another surface, nothing, another medium, or half the echo), until each return's energy is
/// known to the tolerance of itself, or of its (stretched) pulse's threshold when weaker
/// (refinement_settling.h), or the budget is spent.
class CellRefinement final : public FootprintStrategy {
public:
    /// Where the first cells do not settle, they try `edge` (a whole footprint without media or
    /// targets), then `map` where they met the recorded map, before any split (null: neither).
    /// With `map`, a part whose witnesses met the recorded map takes it before any cell: there its
    /// first cells settled 3 % of the time and a straight edge held 3.5 % of the times it was tried
    /// (dataset 2 over Autzen, 20 frames), both costing more than they saved.
    CellRefinement(const FootprintContext& context, RefinementPlan plan, const StraightEdge* edge, const RecordedMapSampling* map)
        : context_(context), plan_(plan), edge_(edge), map_(map) {}

    /// The share it returns is what its kept cells carry.
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;
    /// A target's outline over a recorded map: the final cells whose sub-rays met the map bring
    /// the map's own integration over the region (`rows`: MapRows, which integrates a rectangle),
    /// carrying what they carry, instead of their sub-rays' single ranges.
    void measure_map_by(const FootprintStrategy* rows) { map_cells_ = rows; }

private:
    /// A cell's sub-ray: jittered within it when the render is, keyed by the cell's number (a
    /// `measuring` sub-ray by the other two of the cell's four draws).
    void place(const BeamSetting& beam, RefinementRegion& r, RefinementRegion::Node& n, bool measuring = false) const;
    /// Traces the sub-rays of the cells not traced yet (`measuring`: with volume draws of their own).
    void trace_new_cells(const BeamSetting& beam, RefinementRegion& r, BeamEchoes& out, bool measuring = false) const;
    /// Appends the echoes as they stand: every kept leaf's, weighted by its cell (with
    /// `over_map`, the leaves that met the recorded map by map_cells_ over the region where it can).
    void collect_echoes(RefinementRegion& r, BeamEchoes& out, const BeamSetting* over_map = nullptr) const;
    /// At the first cells, unsettled: a straight edge, or the recorded map's sub-rays. True where
    /// one of them took the part.
    bool first_cells_shortcut(const BeamSetting& beam, const FootprintPart& part, const RefinementRegion& r, BeamEchoes& out) const;
    /// Splits the marked leaves along the axes they disagree across: two children (or four), the
    /// one holding the parent's jittered sub-ray reusing it. False where none could split.
    bool split_marked(const BeamSetting& beam, RefinementRegion& r) const;

    const FootprintContext& context_;
    RefinementPlan plan_;
    const StraightEdge* edge_;
    const RecordedMapSampling* map_;
    const FootprintStrategy* map_cells_ = nullptr;
};

}  // namespace ladarsim::sensor_model
