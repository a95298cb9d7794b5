#include "ladarsim/detect/tracking_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ladarsim::detect {

double ClearMot::mota() const {
    return all.objects > 0 ? 1.0 - double(all.misses + false_positives + all.id_switches) / all.objects
                           : std::numeric_limits<double>::quiet_NaN();
}

double ClearMot::motp_m() const {
    return all.matches > 0 ? all.distance_sum_m / all.matches : std::numeric_limits<double>::quiet_NaN();
}

std::vector<int> least_cost_assignment(const std::vector<std::vector<double>>& cost) {
    // Kuhn-Munkres with potentials on a square matrix (padded with zero-cost dummies), 1-based.
    const std::size_t rows = cost.size(), columns = rows ? cost.front().size() : 0;
    const std::size_t n = std::max(rows, columns);
    auto at = [&](std::size_t i, std::size_t j) { return i < rows && j < columns ? cost[i][j] : 0.0; };
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
    std::vector<std::size_t> p(n + 1, 0), way(n + 1, 0);
    for (std::size_t i = 1; i <= n; ++i) {
        p[0] = i;
        std::size_t j0 = 0;
        std::vector<double> minv(n + 1, inf);
        std::vector<bool> used(n + 1, false);
        do {
            used[j0] = true;
            const std::size_t i0 = p[j0];
            double delta = inf;
            std::size_t j1 = 0;
            for (std::size_t j = 1; j <= n; ++j) {
                if (used[j]) continue;
                const double cur = at(i0 - 1, j - 1) - u[i0] - v[j];
                if (cur < minv[j]) {
                    minv[j] = cur;
                    way[j] = j0;
                }
                if (minv[j] < delta) {
                    delta = minv[j];
                    j1 = j;
                }
            }
            for (std::size_t j = 0; j <= n; ++j) {
                if (used[j]) {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            const std::size_t j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0 != 0);
    }
    std::vector<int> column_of(rows, -1);
    for (std::size_t j = 1; j <= n; ++j)
        if (p[j] >= 1 && p[j] <= rows && j <= columns) column_of[p[j] - 1] = static_cast<int>(j - 1);
    return column_of;
}

ClearMot clear_mot(const std::vector<std::vector<TruthCentre>>& truth, const std::vector<std::vector<TrackCentre>>& tracks,
                   double threshold_m) {
    if (truth.size() != tracks.size()) throw std::invalid_argument("clear_mot: truth and tracks cover different frame counts");
    ClearMot out;
    std::map<std::uint32_t, std::uint32_t> last_track;    // object -> the track it was last matched to
    std::map<std::uint32_t, std::uint32_t> previous;      // last frame's correspondences
    for (std::size_t f = 0; f < truth.size(); ++f) {
        const auto& objects = truth[f];
        const auto& hypotheses = tracks[f];
        std::vector<int> object_match(objects.size(), -1);
        std::vector<bool> taken(hypotheses.size(), false);
        auto distance = [&](std::size_t o, std::size_t h) { return (objects[o].centre - hypotheses[h].centre).norm(); };
        // Last frame's correspondences hold while within the gate.
        for (std::size_t o = 0; o < objects.size(); ++o) {
            const auto it = previous.find(objects[o].id);
            if (it == previous.end()) continue;
            for (std::size_t h = 0; h < hypotheses.size(); ++h) {
                if (taken[h] || hypotheses[h].track != it->second || distance(o, h) > threshold_m) continue;
                object_match[o] = static_cast<int>(h);
                taken[h] = true;
                break;
            }
        }
        // The rest by least total distance, pairs beyond the gate priced out.
        std::vector<std::size_t> free_objects, free_hypotheses;
        for (std::size_t o = 0; o < objects.size(); ++o)
            if (object_match[o] < 0) free_objects.push_back(o);
        for (std::size_t h = 0; h < hypotheses.size(); ++h)
            if (!taken[h]) free_hypotheses.push_back(h);
        if (!free_objects.empty() && !free_hypotheses.empty()) {
            const double out_of_gate = 1e6 * (threshold_m + 1.0);
            std::vector<std::vector<double>> cost(free_objects.size(), std::vector<double>(free_hypotheses.size()));
            for (std::size_t a = 0; a < free_objects.size(); ++a)
                for (std::size_t b = 0; b < free_hypotheses.size(); ++b) {
                    const double d = distance(free_objects[a], free_hypotheses[b]);
                    cost[a][b] = d <= threshold_m ? d : out_of_gate;
                }
            const std::vector<int> column = least_cost_assignment(cost);
            for (std::size_t a = 0; a < free_objects.size(); ++a) {
                if (column[a] < 0) continue;
                const std::size_t o = free_objects[a], h = free_hypotheses[static_cast<std::size_t>(column[a])];
                if (distance(o, h) > threshold_m) continue;
                object_match[o] = static_cast<int>(h);
                taken[h] = true;
            }
        }
        previous.clear();
        for (std::size_t o = 0; o < objects.size(); ++o) {
            ClearMotCounts& c = out.per_class[objects[o].object_class];
            ++c.objects;
            ++out.all.objects;
            if (object_match[o] < 0) {
                ++c.misses;
                ++out.all.misses;
                continue;
            }
            const TrackCentre& h = hypotheses[static_cast<std::size_t>(object_match[o])];
            const double d = distance(o, static_cast<std::size_t>(object_match[o]));
            ++c.matches;
            ++out.all.matches;
            c.distance_sum_m += d;
            out.all.distance_sum_m += d;
            const auto last = last_track.find(objects[o].id);
            if (last != last_track.end() && last->second != h.track) {
                ++c.id_switches;
                ++out.all.id_switches;
            }
            last_track[objects[o].id] = h.track;
            previous[objects[o].id] = h.track;
        }
        out.false_positives += static_cast<int>(std::count(taken.begin(), taken.end(), false));
    }
    return out;
}

double centre_distance_ap(const std::vector<std::vector<TruthCentre>>& truth, const std::vector<std::vector<TrackCentre>>& tracks,
                          double threshold_m, CentreDistance distance, double min_recall, double min_precision) {
    if (truth.size() != tracks.size()) throw std::invalid_argument("centre_distance_ap: truth and tracks cover different frame counts");
    std::size_t positives = 0;
    for (const auto& frame : truth) positives += frame.size();
    if (positives == 0) return std::numeric_limits<double>::quiet_NaN();
    struct Ranked {
        double score;
        std::size_t frame, index;
    };
    std::vector<Ranked> ranked;
    for (std::size_t f = 0; f < tracks.size(); ++f)
        for (std::size_t i = 0; i < tracks[f].size(); ++i) ranked.push_back({tracks[f][i].score, f, i});
    // Highest score first; ties in sequence order, so the result does not depend on the sort.
    std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) { return a.score > b.score; });
    std::vector<std::vector<bool>> matched(truth.size());
    for (std::size_t f = 0; f < truth.size(); ++f) matched[f].assign(truth[f].size(), false);
    std::vector<double> precision, recall;
    double tp = 0.0, fp = 0.0;
    for (const Ranked& r : ranked) {
        const Eigen::Vector3d& c = tracks[r.frame][r.index].centre;
        double best = std::numeric_limits<double>::infinity();
        std::size_t nearest = 0;
        for (std::size_t o = 0; o < truth[r.frame].size(); ++o) {
            if (matched[r.frame][o]) continue;
            const Eigen::Vector3d offset = truth[r.frame][o].centre - c;
            const double d = distance == CentreDistance::ground_plane ? offset.head<2>().norm() : offset.norm();
            if (d < best) {
                best = d;
                nearest = o;
            }
        }
        if (best < threshold_m) {
            matched[r.frame][nearest] = true;
            tp += 1.0;
        } else {
            fp += 1.0;
        }
        precision.push_back(tp / (tp + fp));
        recall.push_back(tp / double(positives));
    }
    if (ranked.empty()) return 0.0;
    // np.interp(r, recall, precision, right=0) at 101 recalls, as nuScenes' accumulate does.
    auto interpolated = [&](double r) {
        if (r < recall.front()) return precision.front();
        std::size_t j = 0;
        while (j + 1 < recall.size() && recall[j + 1] <= r) ++j;
        if (j + 1 == recall.size()) return recall[j] == r ? precision[j] : 0.0;
        return precision[j] + (precision[j + 1] - precision[j]) * (r - recall[j]) / (recall[j + 1] - recall[j]);
    };
    double sum = 0.0;
    int count = 0;
    for (int k = static_cast<int>(std::lround(100.0 * min_recall)) + 1; k <= 100; ++k, ++count)
        sum += std::max(0.0, interpolated(k / 100.0) - min_precision);
    return count ? sum / count / (1.0 - min_precision) : 0.0;
}

CentreDistanceAp centre_distance_aps(const std::vector<std::vector<TruthCentre>>& truth,
                                     const std::vector<std::vector<TrackCentre>>& tracks, CentreDistance distance) {
    CentreDistanceAp ap;
    for (std::size_t k = 0; k < ap.at.size(); ++k) {
        ap.at[k] = centre_distance_ap(truth, tracks, CentreDistanceAp::kThresholds_m[k], distance);
        ap.mean += ap.at[k] / static_cast<double>(ap.at.size());
    }
    return ap;
}

}  // namespace ladarsim::detect
