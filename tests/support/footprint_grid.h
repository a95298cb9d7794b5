#pragma once
// The midpoint rule over a truncated footprint, for tests that integrate it independently of the
// integrator's quadratures and sub-rays.
#include <utility>

namespace ladarsim::test {

/// Calls `cell(x, y)` at the centre of each cell of an n x n grid over the square of half-side
/// `r_max` (offsets in radians) that lies within the truncation radius `r_max`.
template <typename Cell>
void for_each_footprint_cell(int n, double r_max, Cell&& cell) {
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const double x = r_max * (2.0 * (i + 0.5) / n - 1.0), y = r_max * (2.0 * (j + 0.5) / n - 1.0);
            if (x * x + y * y <= r_max * r_max) cell(x, y);
        }
    }
}

}  // namespace ladarsim::test
