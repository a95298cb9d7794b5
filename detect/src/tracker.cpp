#include "ladarsim/detect/tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "ladarsim/detect/box_metrics.h"
#include "ladarsim/core/units.h"

namespace ladarsim::detect {

Method method_from_string(const std::string& name) {
    if (name == "rbnn") return Method::rbnn;
    if (name == "vrbnn") return Method::vrbnn;
    if (name == "kalman") return Method::kalman;
    throw std::invalid_argument("unknown detection method \"" + name + "\" (rbnn, vrbnn or kalman)");
}

std::string to_string(Method m) { return m == Method::rbnn ? "rbnn" : m == Method::vrbnn ? "vrbnn" : "kalman"; }

/// Constant-velocity Kalman filter on the box centre, white acceleration noise.
struct TargetTracker::Kalman {
    Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
    Eigen::Matrix<double, 6, 6> p = Eigen::Matrix<double, 6, 6>::Identity() * 100.0;
    double time_s = 0.0;
    bool started = false;

    void predict(double t, double accel) {
        const double dt = t - time_s;
        Eigen::Matrix<double, 6, 6> f = Eigen::Matrix<double, 6, 6>::Identity();
        f.topRightCorner<3, 3>() = Eigen::Matrix3d::Identity() * dt;
        Eigen::Matrix<double, 6, 6> q = Eigen::Matrix<double, 6, 6>::Zero();
        const double a2 = accel * accel;
        q.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() * a2 * dt * dt * dt * dt / 4.0;
        q.topRightCorner<3, 3>() = Eigen::Matrix3d::Identity() * a2 * dt * dt * dt / 2.0;
        q.bottomLeftCorner<3, 3>() = q.topRightCorner<3, 3>();
        q.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() * a2 * dt * dt;
        x = f * x;
        p = f * p * f.transpose() + q;
        time_s = t;
    }

    /// Mahalanobis distance of a measurement from the prediction.
    double mahalanobis(const Eigen::Vector3d& z, double sigma) const {
        const Eigen::Matrix3d s = p.topLeftCorner<3, 3>() + Eigen::Matrix3d::Identity() * sigma * sigma;
        const Eigen::Vector3d r = z - x.head<3>();
        return std::sqrt(r.dot(s.ldlt().solve(r)));
    }

    void update(const Eigen::Vector3d& z, double sigma) {
        Eigen::Matrix<double, 3, 6> h = Eigen::Matrix<double, 3, 6>::Zero();
        h.leftCols<3>() = Eigen::Matrix3d::Identity();
        const Eigen::Matrix3d s = h * p * h.transpose() + Eigen::Matrix3d::Identity() * sigma * sigma;
        const Eigen::Matrix<double, 6, 3> k = p * h.transpose() * s.inverse();
        x += k * (z - h * x);
        p = (Eigen::Matrix<double, 6, 6>::Identity() - k * h) * p;
    }

    void start(double t, const Eigen::Vector3d& z) {
        x.setZero();
        x.head<3>() = z;
        p = Eigen::Matrix<double, 6, 6>::Identity();
        p.bottomRightCorner<3, 3>() *= 400.0;  // velocity unknown: +-20 m/s
        time_s = t;
        started = true;
    }
};

TargetTracker::TargetTracker(const DetectorConfig& config, const SensorGeometry& sensor, const Points& background_map)
    : config_(config),
      sensor_(sensor),
      background_(background_map, config.background_resolution_m),
      kalman_(std::make_unique<Kalman>()) {}

TargetTracker::~TargetTracker() = default;

std::optional<Eigen::Vector3d> TargetTracker::fir_prediction(double time_s) const {
    if (history_.empty()) return std::nullopt;
    if (history_.size() == 1) return history_.back().second;
    // Least-squares line through the history, evaluated at time_s: an FIR filter whose taps
    // follow from the (time, centre) samples.
    double mean_t = 0.0;
    Eigen::Vector3d mean_c = Eigen::Vector3d::Zero();
    for (const auto& [t, c] : history_) {
        mean_t += t;
        mean_c += c;
    }
    mean_t /= static_cast<double>(history_.size());
    mean_c /= static_cast<double>(history_.size());
    double stt = 0.0;
    Eigen::Vector3d stc = Eigen::Vector3d::Zero();
    for (const auto& [t, c] : history_) {
        stt += (t - mean_t) * (t - mean_t);
        stc += (t - mean_t) * (c - mean_c);
    }
    const Eigen::Vector3d velocity = stt > 0.0 ? Eigen::Vector3d(stc / stt) : Eigen::Vector3d::Zero();
    return mean_c + velocity * (time_s - mean_t);
}

void TargetTracker::remember(double time_s, const OrientedBox& box) {
    history_.emplace_back(time_s, box.centre);
    while (static_cast<int>(history_.size()) > config_.history) history_.pop_front();
    last_size_ = box.size;
}

void TargetTracker::reset(std::uint64_t, double time_s, const OrientedBox& truth) {
    history_.clear();
    line_pairs_.clear();
    remember(time_s, truth);
    last_sensor_size_ = truth.size;
    kalman_->start(time_s, truth.centre);
}

Detection TargetTracker::process(std::uint64_t frame, double time_s, const Points& points,
                                 const std::optional<Eigen::Vector3d>& boresight, const std::vector<float>& intensity) {
    Detection d;
    d.frame = frame;
    d.time_s = time_s;
    const Points foreground = background_.subtract(points);
    const IntensityOf intensity_of = intensity.empty() ? IntensityOf({}, {}) : IntensityOf(points, intensity);

    // calRange: the range of the target the history says we are following.
    std::optional<Eigen::Vector3d> expected = fir_prediction(time_s);
    if (config_.method == Method::kalman && kalman_->started) {
        kalman_->predict(time_s, config_.kalman_accel_mps2);
        expected = kalman_->x.head<3>();
    }
    // calRange: the predicted target's range; with no history yet, the acquisition range (as the
    // tracker of every target takes it; the median, a cloud's range, set a radius below the
    // target's line pitch, which split it into lines that a cloud's nearer clumps outcompeted).
    const double cal_range = expected ? expected->norm() : acquisition_range_m(foreground);
    const auto radius_at = [&](double range_m) {
        return config_.method == Method::rbnn
                   ? config_.rbnn_radius_m
                   : vrbnn_radius_m(config_.lambda.value_or(default_lambda(sensor_)), sensor_, range_m, config_.bias_m);
    };
    d.radius_m = radius_at(cal_range);

    const double divergence_rad = sensor_.divergence_mrad * kMrad;
    const auto min_points = static_cast<std::size_t>(config_.min_neighbours) + 1;
    const double fine_pitch_rad = std::min(sensor_.field_az_deg / sensor_.beams_az, sensor_.field_el_deg / sensor_.beams_el) * kDeg;
    const double line_pitch_rad = sensor_.field_el_deg * kDeg / sensor_.beams_el;
    const double az_pitch_rad = sensor_.field_az_deg * kDeg / sensor_.beams_az;
    // Clutter: a volume's backscatter has no neighbours that agree with it in range.
    const Points coherent = config_.range_coherence_m > 0.0
                                ? without_volume_echoes(foreground, fine_pitch_rad, config_.range_coherence_m, config_.volume_echo_window_m)
                                : foreground;
    const auto candidates_within = [&](double radius_m) {
        const Points kept = config_.range_coherence_m > 0.0 ? remove_incoherent(coherent, radius_m, config_.range_coherence_m, config_.min_neighbours)
                                                            : remove_outliers(foreground, radius_m, config_.min_neighbours);
        std::vector<Cluster> clusters = rbnn(kept, radius_m);
        // Clutter: a cloud's returns chained to the target are cut away, and the tracker takes the
        // core nearest its prediction.
        if (config_.range_coherence_m > 0.0) {
            std::vector<Cluster> cores;
            for (Cluster& c : coherent_cores(clusters, config_.range_coherence_m, min_points)) {
                // A core too large to be the target, where the history says where the target is: a
                // cloud's layer agreeing with it in range, cut away where it does not link to it beam
                // to beam. Not before a history: the pieces of a cloud's cores nearer the cue than
                // the target would be taken (dataset 3's cloud lies before its drone from frame 0).
                if (!expected || small_enough(c, config_.max_diagonal_m, config_.footprint_divergences * divergence_rad))
                    cores.push_back(std::move(c));
                else for (Cluster& piece : beam_connected(c, az_pitch_rad, line_pitch_rad)) cores.push_back(std::move(piece));
            }
            clusters = std::move(cores);
            for (Cluster& c : clusters) {
                std::vector<float> echoes;
                if (!intensity_of.empty())
                    for (const auto& p : c.points) echoes.push_back(intensity_of(p));
                c = without_sparse_lines(c, line_pitch_rad, config_.sparse_line_fraction, echoes);
            }
        }
        return plausible_targets(std::move(clusters), config_.max_diagonal_m, config_.footprint_divergences * divergence_rad, min_points);
    };
    std::vector<Cluster> candidates = candidates_within(d.radius_m);

    // The candidate: nearest the expected position when there is one, else nearest the boresight
    // (the radar cue put the target there), else the largest.
    const bool gating = config_.method == Method::kalman && kalman_->started;
    const Cluster* chosen = nullptr;
    double best = std::numeric_limits<double>::infinity();
    const auto choose = [&] {
        chosen = nullptr;
        best = std::numeric_limits<double>::infinity();
        for (const Cluster& c : candidates) {
            const double distance = gating      ? kalman_->mahalanobis(c.box.centre, config_.kalman_measurement_m)
                                    : expected  ? (c.box.centre - *expected).norm()
                                    : boresight ? std::acos(std::clamp(c.box.centre.normalized().dot(*boresight), -1.0, 1.0))
                                                : -static_cast<double>(c.points.size());
            if (distance < best) {
                best = distance;
                chosen = &c;
            }
        }
    };
    choose();
    // Before a history the acquisition range was a guess: once the cue has picked a candidate, its
    // own range sets the radius and the frame is clustered again (dataset 3's frame 0: the cloud's
    // range, 650 m, set 0.35 m, under the 0.39 m between the drone's two lines at 900 m, and the
    // box took one of them, 0.2 m off).
    if (!expected && chosen) {
        const double radius_m = radius_at(chosen->box.centre.norm());
        if (radius_m != d.radius_m) {
            d.radius_m = radius_m;
            candidates = candidates_within(radius_m);
            choose();
        }
    }
    if (chosen && expected) {
        const double since_s = history_.empty() ? 0.0 : time_s - history_.back().first;
        const bool jump = gating
                              ? best > config_.kalman_gate_sigmas
                              : std::abs(chosen->box.centre.norm() - expected->norm()) > config_.max_speed_mps * since_s + 0.5;
        if (jump) chosen = nullptr;
    }
    if (chosen) {
        d.found = true;
        d.box = chosen->box;
        d.box.size = d.box.size.cwiseMax(Eigen::Vector3d::Constant(config_.min_box_m));
        d.sensor_box = sensor_aware_box(chosen->box, config_.footprint_divergences * divergence_rad, config_.target_size_m);
        if (!intensity.empty() && config_.min_peak_ratio > 0.0) {
            std::vector<float> echoes;
            for (const auto& p : chosen->points) echoes.push_back(intensity_of(p));
            if (const auto pair = strongest_line_pair(chosen->points, echoes, line_pitch_rad)) {
                // The target crossed to another pair of lines: its offset from their midpoint jumped.
                // The lines move with the gimbal, so pairs are compared about the boresight (dataset 3
                // over Autzen: the gimbal follows the diving drone a line pitch a frame, and the same
                // pair about it lay a pitch lower in every frame).
                LinePair about_boresight = *pair;
                if (boresight) {
                    const double boresight_el = std::asin(std::clamp(boresight->z(), -1.0, 1.0));
                    about_boresight.lower_rad -= boresight_el;
                    about_boresight.upper_rad -= boresight_el;
                }
                if (!line_pairs_.empty() && std::abs(line_pairs_.back().lower_rad - about_boresight.lower_rad) > 0.5 * line_pitch_rad)
                    line_pairs_.clear();
                line_pairs_.push_back(about_boresight);
                while (static_cast<int>(line_pairs_.size()) > config_.line_profile_frames) line_pairs_.pop_front();
                double log_ratio = 0.0;
                for (const LinePair& l : line_pairs_) log_ratio += l.log_ratio;
                log_ratio /= static_cast<double>(line_pairs_.size());
                if (std::abs(log_ratio) >= std::log(config_.min_peak_ratio))
                    d.sensor_box.centre = at_elevation(d.sensor_box.centre, elevation_between(*pair, log_ratio, 0.5 * divergence_rad));
            }
        }
        last_sensor_size_ = d.sensor_box.size;
        d.points = chosen->points.size();
        remember(time_s, d.box);
        if (config_.method == Method::kalman) {
            if (kalman_->started) kalman_->update(d.box.centre, config_.kalman_measurement_m);
            else kalman_->start(time_s, d.box.centre);
        }
    } else if (expected) {
        d.found = true;
        d.predicted = true;
        d.box.centre = *expected;
        d.box.size = last_size_;
        d.sensor_box.centre = *expected;
        d.sensor_box.size = last_sensor_size_;
    }
    return d;
}

}  // namespace ladarsim::detect
