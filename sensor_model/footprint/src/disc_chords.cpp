#include "ladarsim/sensor_model/footprint/disc_chords.h"

#include <algorithm>
#include <cmath>

namespace ladarsim::sensor_model {

bool disc_chord(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double r, double X, double t_min, double t_max, DiscChord& out) {
    // The plane of the line's directions has normal m = (X, -1, 0); it cuts the disc's plane along
    // l = m x n, and the disc where the cut passes within r of its centre: at mu = -(m . p) / |l|
    // along u = n x l / |l| (m . (n x l) = |l|^2). Written out by component: every beam asks
    // this of each disc on each line, and only x and z of the chord's ends are needed.
    const double nx = n.x(), ny = n.y(), nz = n.z();
    const double lz = nx + X * ny;
    const double l2 = nz * nz * (1.0 + X * X) + lz * lz;
    const double mp = X * p.x() - p.y();
    if (!(mp * mp < r * r * l2)) return false;  // misses the disc (or l = 0: the planes are parallel)
    const double l_norm = std::sqrt(l2);
    const double mu = -mp / l_norm;
    const double h = std::sqrt(r * r - mu * mu);
    const double ux = (ny * lz + X * nz * nz) / l_norm, uz = nz * (ny - X * nx) / l_norm;
    const double q0x = p.x() + mu * ux, q0z = p.z() + mu * uz;
    const double hlx = -h * nz / l_norm, hlz = h * lz / l_norm;
    const double ax = q0x + hlx, bx = q0x - hlx;
    if (!(ax > 0.0 && bx > 0.0)) return false;
    const double ta = (q0z + hlz) / ax, tb = (q0z - hlz) / bx;
    out.t_lo = std::max(std::min(ta, tb), t_min);
    out.t_hi = std::min(std::max(ta, tb), t_max);
    if (!(out.t_lo < out.t_hi)) return false;
    // Along (1, X, t) the plane n . (q - p) = 0 is at distance s = (n . p) / (n . (1, X, t)).
    const double c = n.dot(p);
    if (std::abs(c) < 1e-12) return false;
    out.g0 = lz / c;
    out.g1 = nz / c;
    return true;
}

void lower_envelope(std::vector<DiscChord>& chords, double t0, double t1, std::vector<VisiblePiece>& out) {
    // Sweep the chords' ends in order; between two ends the chords present are fixed, and the
    // nearest of them changes only where a nearer one crosses it (each pair at most once).
    thread_local std::vector<double> ends;
    thread_local std::vector<std::uint32_t> active;
    ends.clear();
    ends.push_back(t0);
    ends.push_back(t1);
    for (const DiscChord& c : chords) {
        if (c.t_lo > t0 && c.t_lo < t1) ends.push_back(c.t_lo);
        if (c.t_hi > t0 && c.t_hi < t1) ends.push_back(c.t_hi);
    }
    std::sort(ends.begin(), ends.end());
    std::sort(chords.begin(), chords.end(), [](const DiscChord& a, const DiscChord& b) { return a.t_lo < b.t_lo; });
    active.clear();
    std::size_t next = 0;
    auto append = [&](double a, double b, std::uint32_t disc, double g0, double g1) {
        if (!(b > a)) return;
        if (!out.empty() && out.back().disc == disc && out.back().t_hi == a && (disc == kGapPiece || (out.back().g0 == g0 && out.back().g1 == g1))) {
            out.back().t_hi = b;
            return;
        }
        out.push_back({a, b, disc, g0, g1});
    };
    for (std::size_t e = 0; e + 1 < ends.size(); ++e) {
        const double a = ends[e], b = ends[e + 1];
        if (!(b > a)) continue;
        const double mid = 0.5 * (a + b);
        std::erase_if(active, [&](std::uint32_t k) { return chords[k].t_hi <= mid; });
        while (next < chords.size() && chords[next].t_lo <= mid) {
            if (chords[next].t_hi > mid) active.push_back(static_cast<std::uint32_t>(next));
            ++next;
        }
        if (active.empty()) {
            append(a, b, kGapPiece, 0.0, 0.0);
            continue;
        }
        // The nearest at a (ties: the one nearer just after a).
        auto g = [&](std::uint32_t k, double t) { return chords[k].g0 + chords[k].g1 * t; };
        std::uint32_t best = active[0];
        for (const std::uint32_t k : active) {
            const double dk = g(k, a) - g(best, a);
            if (dk > 0.0 || (dk == 0.0 && chords[k].g1 > chords[best].g1)) best = k;
        }
        double t = a;
        for (;;) {
            double cross = b;
            std::uint32_t taker = best;
            for (const std::uint32_t k : active) {
                const double dg1 = chords[k].g1 - chords[best].g1;
                if (!(dg1 > 0.0)) continue;
                const double tc = t + (g(best, t) - g(k, t)) / dg1;
                if (tc > t && tc < cross) {
                    cross = tc;
                    taker = k;
                }
            }
            append(t, cross, chords[best].disc, chords[best].g0, chords[best].g1);
            if (taker == best) break;
            t = cross;
            best = taker;
        }
    }
}

}  // namespace ladarsim::sensor_model
