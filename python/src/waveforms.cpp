// ladarsim.read_waveforms: a frame's full waveforms (waveforms/NNNNNN.h5) as NumPy arrays.
#include <filesystem>

#include <pybind11/numpy.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "ladarsim/dataset/waveform_file.h"

namespace ladarsim::python {

namespace {

template <typename T, typename Field>
py::array_t<T> column_of(const std::vector<WaveformWindow>& windows, Field field) {
    py::array_t<T> array(static_cast<py::ssize_t>(windows.size()));
    auto out = array.template mutable_unchecked<1>();
    for (std::size_t i = 0; i < windows.size(); ++i) out(static_cast<py::ssize_t>(i)) = static_cast<T>(field(windows[i]));
    return array;
}

py::dict read_waveforms(const std::filesystem::path& file) {
    FrameWaveforms w;
    {
        py::gil_scoped_release release;
        w = read_waveforms_h5(file);
    }
    py::list samples;
    for (const WaveformWindow& window : w.windows)
        samples.append(py::array_t<float>(static_cast<py::ssize_t>(window.samples_a.size()), window.samples_a.data()));
    const WaveformReceiverInfo& r = w.receiver;
    py::dict d;
    d["frame"] = w.frame;
    d["column"] = column_of<std::uint16_t>(w.windows, [](const WaveformWindow& x) { return x.column; });
    d["row"] = column_of<std::uint16_t>(w.windows, [](const WaveformWindow& x) { return x.row; });
    d["time_s"] = column_of<double>(w.windows, [](const WaveformWindow& x) { return x.time_s; });
    d["start_s"] = column_of<double>(w.windows, [](const WaveformWindow& x) { return x.start_s; });
    d["samples"] = samples;
    d["sample_interval_s"] = r.sample_interval_s;
    d["pulse_fwhm_s"] = r.pulse_fwhm_s;
    d["threshold_a"] = r.threshold_a;
    d["release_a"] = r.release_a;
    d["noise_floor_a"] = r.noise_floor_a;
    d["saturation_a"] = r.saturation_a;
    d["photoelectrons_per_coulomb"] = r.photoelectrons_per_coulomb;
    return d;
}

}  // namespace

void bind_waveforms(py::module_& m) {
    m.def("read_waveforms", &read_waveforms, py::arg("file"),
          R"(A frame's full waveforms (a render with render.waveforms: true writes DIR/waveforms/NNNNNN.h5): a dict of
column, row (uint16), time_s (the pulse's emission), start_s (the window's first sample after it) per window,
samples (a list of float32 arrays, the detector's current in amperes), and the receiver's sample_interval_s,
pulse_fwhm_s, threshold_a, release_a, noise_floor_a, saturation_a and photoelectrons_per_coulomb (intensity =
sum(samples) x sample_interval_s x this). See docs/waveforms.md.)");
}

}  // namespace ladarsim::python
