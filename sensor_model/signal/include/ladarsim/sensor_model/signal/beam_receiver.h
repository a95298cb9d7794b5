#pragma once
// From the echoes of one beam's sub-rays to what the sensor reports: speckle, range folding,
// detection against the noise, timing jitter, saturation, false alarms, and which returns are kept.
// A beam that meets one surface takes a closed form; only beams meeting several build a waveform.
#include <cstdint>
#include <vector>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/sensor_model/signal/apd_receiver.h"
#include "ladarsim/sensor_model/signal/atmosphere.h"
#include "ladarsim/sensor_model/signal/counter_random.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/sensor_model/signal/waveform.h"

namespace ladarsim::sensor_model {

/// One distinct surface (or volume) along a beam, with the echoes of the sub-rays that met it.
struct BeamSurface {
    std::uint32_t object_id = 0;
    ReturnSource source = ReturnSource::surface;
    double weight = 0.0;      ///< share of the beam's energy that met it (sum of sub-ray weights)
    std::vector<Echo> echoes; ///< true ranges; `surface` fields are set by BeamReceiver
    /// Its echoes draw its range profile piece by piece (a recorded map's discs: the pieces of
    /// lines across them, or sub-rays' points on them), not as patches that carry only their
    /// spread. Alone in a beam, it
    /// takes the closed form (one Gaussian pulse) where its echoes' centres lie within the pulse's
    /// sigma, where their pulses add to one peak however they lie (two equal ones 2 sigma apart
    /// are the widest pair that does), or where it is weak (kResolvedPeaks); deeper and strong (a
    /// stadium's stands), its waveform is drawn, so that whether a few discs left a gap in range,
    /// splitting it in two surfaces, does not decide between one return and seven.
    bool profiled = false;
};

/// A return before its beam geometry (direction, raster cell) is attached.
struct DetectedReturn {
    double range_m;           ///< as reported: folded when ranges fold
    double energy_j;          ///< measured energy (from the measured peak; clipped when saturated)
    double snr;
    bool saturated;
    std::uint32_t object_id;
    ReturnSource source;
    std::uint8_t pulse_offset;
};

/// Keys of one beam's random draws.
struct BeamKey {
    std::uint64_t seed;
    std::uint64_t frame;
    std::uint32_t beam;
};

class BeamReceiver {
public:
    /// `noise` false: no speckle, detector noise, jitter or false alarms (expectations only).
    BeamReceiver(const Sensor& sensor, const Atmosphere& atmosphere, bool noise = true);

    /// Detected returns of one beam, sorted by reported range, filtered by `reported_returns`.
    std::vector<DetectedReturn> receive(std::vector<BeamSurface> surfaces, const BeamKey& key) const;
    /// The same into `returns` (cleared first), working on `surfaces` in place: a renderer reuses
    /// both from beam to beam and allocates nothing once they are warm. With `windows` set, every
    /// beam is detected in its sampled waveform, a beam meeting one surface too (not by the closed
    /// form, which draws its noise differently), and the windows searched are appended to it
    /// (start_s and samples_a): the returns other than false alarms are what the discriminator
    /// found in them. False alarms are drawn for the whole range gate, outside any window.
    void receive(std::vector<BeamSurface>& surfaces, const BeamKey& key, std::vector<DetectedReturn>& returns,
                 std::vector<WaveformWindow>* windows = nullptr) const;

    const ApdReceiver& apd() const { return apd_; }
    const WaveformReceiver& waveform() const { return waveform_; }
    /// One-way transmission of the clear air over `range_m`.
    double transmission(double range_m) const;
    /// The clear air's extinction coefficient at the sensor's wavelength.
    double extinction_per_m() const { return extinction_per_m_; }
    /// Echoes from closer than this are never seen (the detector is blind from the outgoing pulse).
    double min_range_m() const { return sensor_.receiver.min_range_m; }

private:
    DetectedReturn closed_form(const BeamSurface& surface, RandomSequence& noise) const;
    void add_false_alarms(std::vector<DetectedReturn>& returns, const BeamKey& key) const;
    /// Moves a measured range into the gate of the pulse that received it: [0, c / (2 PRF)).
    void fold(DetectedReturn& r) const;

    Sensor sensor_;
    bool noise_;
    double extinction_per_m_;
    ApdReceiver apd_;
    WaveformReceiver waveform_;
    double unambiguous_range_m_;
    double false_alarms_per_gate_;  ///< their mean count in one range gate, and exp(-it): drawn every beam
    double no_false_alarm_;
    double pulse_sigma_m_;    ///< the pulse's sigma in range
    double resolved_peak_j_;  ///< a deep map surface's closed-form peak from which its waveform is drawn
};

}  // namespace ladarsim::sensor_model
