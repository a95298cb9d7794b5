#include "ladarsim/sensor_model/footprint.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ladarsim::sensor_model {

Footprint::Footprint(double divergence_rad, int samples, double truncation)
    : waist_rad_(0.5 * divergence_rad), max_radius_rad_(truncation * 0.5 * divergence_rad) {
    if (!(divergence_rad > 0.0) || samples < 1 || !(truncation > 0.0)) {
        throw std::invalid_argument("footprint needs a positive divergence, sample count and truncation");
    }
    const double captured = -std::expm1(-2.0 * truncation * truncation);
    const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    const int rings = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples)))));
    cells_.reserve(static_cast<std::size_t>(samples));
    int first = 0;
    for (int ring = 0; ring < rings; ++ring) {
        const int in_ring = samples / rings + (ring < samples % rings ? 1 : 0);
        const double lo = captured * first / samples;
        const double hi = captured * (first + in_ring) / samples;
        const double sector = 2.0 * std::numbers::pi / in_ring;
        const double turn = golden_angle * ring;
        for (int k = 0; k < in_ring; ++k) {
            cells_.push_back({lo, hi, turn + k * sector, turn + (k + 1) * sector});
        }
        first += in_ring;
    }
}

SubRay Footprint::place(const Cell& cell, double u_energy, double u_angle) const {
    // Invert the enclosed energy F(r) = 1 - exp(-2 r^2 / w^2).
    const double energy = cell.energy_lo + u_energy * (cell.energy_hi - cell.energy_lo);
    const double radius = waist_rad_ * std::sqrt(-0.5 * std::log1p(-energy));
    const double angle = cell.angle_lo_rad + u_angle * (cell.angle_hi_rad - cell.angle_lo_rad);
    return {radius * std::cos(angle), radius * std::sin(angle), 1.0 / static_cast<double>(cells_.size())};
}

void Footprint::fixed(std::span<SubRay> out) const {
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        // A lone sample stands for the whole disc: its natural place is the beam axis.
        out[i] = cells_.size() == 1 ? SubRay{0.0, 0.0, 1.0} : place(cells_[i], 0.5, 0.5);
    }
}

void Footprint::jittered(std::span<SubRay> out, std::span<const double> uniforms) const {
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        out[i] = place(cells_[i], uniforms[2 * i], uniforms[2 * i + 1]);
    }
}

}  // namespace ladarsim::sensor_model
