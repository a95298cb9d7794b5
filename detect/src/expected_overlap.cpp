#include "ladarsim/detect/expected_overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace ladarsim::detect {

std::vector<Fragment> fragments_of(const std::vector<double>& overlap, const std::vector<bool>& initialised) {
    std::vector<Fragment> out;
    bool running = false;
    for (std::size_t i = 0; i < overlap.size(); ++i) {
        if (initialised[i]) {
            if (running) out.back().ends_in_failure = false;
            out.emplace_back();
            running = true;
        }
        if (!running) continue;  // skipped frames after a failure
        out.back().overlaps.push_back(overlap[i]);
        if (overlap[i] <= 0.0 && !initialised[i]) {
            out.back().ends_in_failure = true;
            running = false;
        }
    }
    return out;
}

double expected_overlap(const std::vector<Fragment>& fragments, int n) {
    if (n < 2) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0.0;
    int usable = 0;
    for (const Fragment& f : fragments) {
        const int length = static_cast<int>(f.overlaps.size());
        if (!f.ends_in_failure && length < n) continue;
        double s = 0.0;
        for (int i = 1; i < std::min(length, n); ++i) s += f.overlaps[static_cast<std::size_t>(i)];  // zeros past a failure
        sum += s / (n - 1);
        ++usable;
    }
    return usable ? sum / usable : std::numeric_limits<double>::quiet_NaN();
}

double expected_average_overlap(const std::vector<Fragment>& fragments, int lo, int hi) {
    double sum = 0.0;
    int count = 0;
    for (int n = std::max(lo, 2); n <= hi; ++n) {
        const double phi = expected_overlap(fragments, n);
        if (std::isnan(phi)) continue;
        sum += phi;
        ++count;
    }
    return count ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

std::pair<int, int> vot_length_interval(const std::vector<int>& lengths) {
    if (lengths.empty()) return {0, 0};
    const auto [min_it, max_it] = std::minmax_element(lengths.begin(), lengths.end());
    if (*min_it == *max_it) return {*min_it, *max_it};
    const double n = static_cast<double>(lengths.size());
    const double mean = std::accumulate(lengths.begin(), lengths.end(), 0.0) / n;
    double var = 0.0;
    for (int l : lengths) var += (l - mean) * (l - mean);
    const double bandwidth = std::max(1.0, 1.06 * std::sqrt(var / n) * std::pow(n, -0.2));
    const int lo_grid = std::max(1, static_cast<int>(*min_it - 3 * bandwidth)), hi_grid = static_cast<int>(*max_it + 3 * bandwidth);
    std::vector<double> density(static_cast<std::size_t>(hi_grid - lo_grid + 1));
    for (int x = lo_grid; x <= hi_grid; ++x)
        for (int l : lengths) density[static_cast<std::size_t>(x - lo_grid)] += std::exp(-0.5 * std::pow((x - l) / bandwidth, 2));
    const double total = std::accumulate(density.begin(), density.end(), 0.0);
    std::size_t lo = static_cast<std::size_t>(std::max_element(density.begin(), density.end()) - density.begin()), hi = lo;
    double mass = density[lo];
    // Grow towards the denser side until half the mass is inside.
    while (mass < 0.5 * total) {
        const double left = lo > 0 ? density[lo - 1] : -1.0, right = hi + 1 < density.size() ? density[hi + 1] : -1.0;
        if (left >= right) mass += density[--lo];
        else mass += density[++hi];
    }
    return {lo_grid + static_cast<int>(lo), lo_grid + static_cast<int>(hi)};
}

}  // namespace ladarsim::detect
