#pragma once
// A frame's full waveforms (render.waveforms: true) as HDF5, waveforms/NNNNNN.h5: for each stretch
// of a beam's received waveform the discriminator searched (a window), the detector's current
// sample by sample, noise and clipping included. Layout (docs/waveforms.md):
//   /column, /row        uint16, one per window: the beam's raster cell
//   /time_s              float64: the beam's pulse emission time (the frame's clock)
//   /start_s             float64: time of the window's first sample after the emission (range time)
//   /first_sample        uint64: where the window's samples start in /samples
//   /sample_count        uint32
//   /samples             float32: every window's samples, one after another, amperes
// and attributes on the root: frame (uint64), sample_interval_s, pulse_fwhm_s, threshold_a,
// release_a, noise_floor_a, saturation_a, photoelectrons_per_coulomb (the intensity a current
// summed over time makes, as frames report intensity), units.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace ladarsim {

/// One window of one beam's digitised waveform.
struct WaveformWindow {
    std::uint16_t column = 0;
    std::uint16_t row = 0;
    double time_s = 0.0;
    double start_s = 0.0;
    std::vector<float> samples_a;
};

/// The receiver's constants a reader needs to read the samples as the detector did.
struct WaveformReceiverInfo {
    double sample_interval_s = 0.0;
    double pulse_fwhm_s = 0.0;
    double threshold_a = 0.0;   ///< an excursion starts above this
    double release_a = 0.0;     ///< and ends at or below this
    double noise_floor_a = 0.0;
    double saturation_a = 0.0;
    double photoelectrons_per_coulomb = 0.0;
};

struct FrameWaveforms {
    std::uint64_t frame = 0;
    WaveformReceiverInfo receiver;
    std::vector<WaveformWindow> windows;
};

/// Writes `waveforms` (atomically: under a temporary name, then renamed), deterministically: the
/// same waveforms give the same bytes (no object times recorded). The samples are compressed
/// (shuffle and deflate) in chunks. Throws std::runtime_error naming the file when HDF5 fails.
void write_waveforms_h5(const std::filesystem::path& path, const FrameWaveforms& waveforms);

/// Reads a file write_waveforms_h5 wrote. Throws InputError naming the file and the dataset or
/// attribute that is missing or inconsistent.
FrameWaveforms read_waveforms_h5(const std::filesystem::path& path);

}  // namespace ladarsim
