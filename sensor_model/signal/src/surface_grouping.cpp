#include "ladarsim/sensor_model/signal/surface_grouping.h"

#include <array>
#include <cstring>
#include <utility>

namespace ladarsim::sensor_model {

namespace {

/// Indices of `echoes` in order of (object id, range), stable. Most beams bring one or two echoes
/// (an insertion sort: std::stable_sort allocates a buffer on every call); a beam over a recorded
/// map brings hundreds, where a comparison sort's mispredicted branches cost three times a
/// least-significant-digit radix sort on the object id and the range as a float (rounding to float
/// keeps the order, merely making a few near neighbours equal, whose order an insertion pass over
/// the exact ranges then settles: the same order as a stable sort on the exact keys).
void sort_by_object_and_range(const std::vector<SurfaceEcho>& echoes, std::vector<std::uint32_t>& order) {
    const std::size_t n = echoes.size();
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
    auto before = [&](std::uint32_t a, std::uint32_t b) {
        const SurfaceEcho &x = echoes[a], &y = echoes[b];
        return x.object_id != y.object_id ? x.object_id < y.object_id : x.range_m < y.range_m;
    };
    auto insertion = [&] {
        for (std::size_t i = 1; i < n; ++i) {
            const std::uint32_t v = order[i];
            std::size_t j = i;
            for (; j > 0 && before(v, order[j - 1]); --j) order[j] = order[j - 1];
            order[j] = v;
        }
    };
    if (n < 64) {
        insertion();
        return;
    }
    // Eight bytes a key: four of the range as a float (low first), then four of the object id.
    // Only the bytes that differ between keys are counted and sorted on (a map's beam: its ranges'
    // three low bytes, one object): a byte every key shares leaves the order as it is.
    thread_local std::vector<std::array<std::uint32_t, 2>> keys;
    keys.resize(n);
    std::array<std::uint32_t, 2> differ{};
    for (std::size_t i = 0; i < n; ++i) {
        // +0 for a negative zero or any negative range (none reaches here), so that bits order.
        const float range = echoes[i].range_m > 0.0 ? static_cast<float>(echoes[i].range_m) : 0.0f;
        std::uint32_t bits;
        std::memcpy(&bits, &range, sizeof bits);
        keys[i] = {bits, echoes[i].object_id};
        differ[0] |= bits ^ keys[0][0];
        differ[1] |= echoes[i].object_id ^ keys[0][1];
    }
    thread_local std::vector<std::uint32_t> other;
    other.resize(n);
    for (int b = 0; b < 8; ++b) {
        const std::size_t word = static_cast<std::size_t>(b / 4);
        const int shift = 8 * (b % 4);
        if (!((differ[word] >> shift) & 0xFFu)) continue;
        std::array<std::uint32_t, 256> count{};
        for (std::size_t i = 0; i < n; ++i) ++count[(keys[i][word] >> shift) & 0xFFu];
        std::uint32_t start = 0;
        for (std::uint32_t& c : count) {
            const std::uint32_t here = c;
            c = start;
            start += here;
        }
        for (const std::uint32_t i : order) other[count[(keys[i][word] >> shift) & 0xFFu]++] = i;
        order.swap(other);
    }
    insertion();
}

}  // namespace

std::vector<BeamSurface> gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m, std::vector<std::uint32_t>* surface_of_echo) {
    std::vector<BeamSurface> surfaces;
    gather_surfaces(echoes, gap_m, surfaces, surface_of_echo);
    return surfaces;
}

void gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m, std::vector<BeamSurface>& surfaces,
                     std::vector<std::uint32_t>* surface_of_echo) {
    // One object at a time: a surface is one object's, so that a return always names the object
    // whose echo made it (ground running into a wall's foot stays ground, the wall stays the wall;
    // their pulses still merge in the waveform when they overlap). Sorted by (object, range),
    // echoes of equal keys in the order they came, then moved once.
    thread_local std::vector<std::uint32_t> order;
    sort_by_object_and_range(echoes, order);
    thread_local std::vector<SurfaceEcho> sorted;
    sorted.clear();
    for (const std::uint32_t i : order) sorted.push_back(echoes[i]);
    echoes.swap(sorted);
    if (surface_of_echo) surface_of_echo->resize(echoes.size());
    // Echo lists of surfaces dropped from the end, kept for the next beam that needs more.
    thread_local std::vector<std::vector<Echo>> spare;
    std::size_t count = 0;
    for (std::size_t first = 0; first < echoes.size();) {
        std::size_t last = first + 1;
        while (last < echoes.size() && echoes[last].object_id == echoes[first].object_id &&
               same_surface(echoes[last - 1], echoes[last], gap_m))
            ++last;
        if (count == surfaces.size()) {
            surfaces.emplace_back();
            if (!spare.empty()) {
                surfaces.back().echoes = std::move(spare.back());
                spare.pop_back();
            }
        }
        BeamSurface& surface = surfaces[count++];
        surface.echoes.clear();
        surface.weight = 0.0;
        surface.source = ReturnSource::surface;
        surface.object_id = echoes[first].object_id;
        for (std::size_t k = first; k < last; ++k) {
            surface.weight += echoes[k].weight;
            // A sub-ray stands for its cell of the surface, which reaches about half-way to the
            // ranges of its neighbours: its pulse is stretched by that much, so that a sparsely
            // sampled surface draws one continuous echo, not a comb of spurious peaks.
            const double before = k > first ? echoes[k].range_m - echoes[k - 1].range_m : 0.0;
            const double after = k + 1 < last ? echoes[k + 1].range_m - echoes[k].range_m : 0.0;
            const double spread = std::max(echoes[k].spread_m, 0.5 * std::max(before, after));
            surface.echoes.push_back({echoes[k].range_m, echoes[k].energy_j, 0, spread});
            if (surface_of_echo) (*surface_of_echo)[k] = static_cast<std::uint32_t>(count - 1);
        }
        first = last;
    }
    // (A few: volume surfaces arrive with lists of their own, which would otherwise pile up.)
    for (std::size_t i = count; i < surfaces.size() && spare.size() < 16; ++i) {
        surfaces[i].echoes.clear();
        spare.push_back(std::move(surfaces[i].echoes));
    }
    surfaces.resize(count);
}

}  // namespace ladarsim::sensor_model
