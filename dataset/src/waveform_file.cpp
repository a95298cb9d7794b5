#include "ladarsim/dataset/waveform_file.h"

#include <hdf5.h>

#include <stdexcept>
#include <string>

#include "ladarsim/core/input_error.h"

namespace ladarsim {

namespace {

/// Closes an HDF5 identifier when it goes out of scope (identifiers below 0 are HDF5's failures).
class Handle {
public:
    Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
    ~Handle() {
        if (id_ >= 0) close_(id_);
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    hid_t get() const { return id_; }
    bool ok() const { return id_ >= 0; }

private:
    hid_t id_;
    herr_t (*close_)(hid_t);
};

constexpr hsize_t kChunk = 1 << 16;  // samples per compressed chunk: 256 kB

/// Silences HDF5's own error printing while this lives: failures are reported as one line naming the file.
class QuietHdf5 {
public:
    QuietHdf5() {
        H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    }
    ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
    QuietHdf5(const QuietHdf5&) = delete;
    QuietHdf5& operator=(const QuietHdf5&) = delete;

private:
    H5E_auto2_t function_ = nullptr;
    void* data_ = nullptr;
};

void check(bool ok, const std::filesystem::path& path, const std::string& what) {
    if (!ok) throw std::runtime_error(path.string() + ": cannot write the waveforms (HDF5, " + what + ")");
}

template <typename T>
void write_column(hid_t file, const char* name, hid_t type, const std::vector<T>& values, const std::filesystem::path& path,
                  bool compress) {
    const hsize_t n = values.size();
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    check(space.ok() && properties.ok(), path, name);
    H5Pset_obj_track_times(properties.get(), false);  // no creation times: the same frame, the same bytes
    if (compress && n > 0) {
        const hsize_t chunk = std::min<hsize_t>(n, kChunk);
        H5Pset_chunk(properties.get(), 1, &chunk);
        H5Pset_shuffle(properties.get());
        H5Pset_deflate(properties.get(), 4);
    }
    Handle set(H5Dcreate2(file, name, type, space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT), H5Dclose);
    check(set.ok(), path, name);
    if (n > 0) check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0, path, name);
}

template <typename T>
void write_attribute(hid_t file, const char* name, hid_t type, T value, const std::filesystem::path& path) {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(H5Acreate2(file, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(attribute.ok() && H5Awrite(attribute.get(), type, &value) >= 0, path, name);
}

void write_text_attribute(hid_t file, const char* name, const std::string& text, const std::filesystem::path& path) {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type.get(), text.size());
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attribute(H5Acreate2(file, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    check(attribute.ok() && H5Awrite(attribute.get(), type.get(), text.data()) >= 0, path, name);
}

template <typename T>
std::vector<T> read_column(hid_t file, const char* name, hid_t type, const std::filesystem::path& path) {
    Handle set(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose);
    if (!set.ok()) throw InputError(path.string(), name, "missing: not a waveform file ladarsim wrote");
    Handle space(H5Dget_space(set.get()), H5Sclose);
    if (H5Sget_simple_extent_ndims(space.get()) != 1) throw InputError(path.string(), name, "is not one-dimensional");
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space.get(), &n, nullptr);
    std::vector<T> values(n);
    if (n > 0 && H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
        throw InputError(path.string(), name, "cannot be read");
    return values;
}

template <typename T>
T read_attribute(hid_t file, const char* name, hid_t type, const std::filesystem::path& path) {
    Handle attribute(H5Aopen(file, name, H5P_DEFAULT), H5Aclose);
    T value{};
    if (!attribute.ok() || H5Aread(attribute.get(), type, &value) < 0)
        throw InputError(path.string(), std::string("attribute ") + name, "missing: not a waveform file ladarsim wrote");
    return value;
}

}  // namespace

void write_waveforms_h5(const std::filesystem::path& path, const FrameWaveforms& waveforms) {
    const QuietHdf5 quiet;
    std::vector<std::uint16_t> column, row;
    std::vector<double> time, start;
    std::vector<std::uint64_t> first;
    std::vector<std::uint32_t> count;
    std::vector<float> samples;
    for (const WaveformWindow& w : waveforms.windows) {
        column.push_back(w.column);
        row.push_back(w.row);
        time.push_back(w.time_s);
        start.push_back(w.start_s);
        first.push_back(samples.size());
        count.push_back(static_cast<std::uint32_t>(w.samples_a.size()));
        samples.insert(samples.end(), w.samples_a.begin(), w.samples_a.end());
    }
    const std::filesystem::path temporary = path.string() + ".tmp";
    {
        Handle creation(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
        check(creation.ok(), path, "file properties");
        H5Pset_obj_track_times(creation.get(), false);
        Handle file(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, creation.get(), H5P_DEFAULT), H5Fclose);
        check(file.ok(), path, "create " + temporary.string());
        const hid_t f = file.get();
        write_column(f, "column", H5T_NATIVE_UINT16, column, path, false);
        write_column(f, "row", H5T_NATIVE_UINT16, row, path, false);
        write_column(f, "time_s", H5T_NATIVE_DOUBLE, time, path, false);
        write_column(f, "start_s", H5T_NATIVE_DOUBLE, start, path, false);
        write_column(f, "first_sample", H5T_NATIVE_UINT64, first, path, false);
        write_column(f, "sample_count", H5T_NATIVE_UINT32, count, path, false);
        write_column(f, "samples", H5T_NATIVE_FLOAT, samples, path, true);
        const WaveformReceiverInfo& r = waveforms.receiver;
        write_attribute(f, "frame", H5T_NATIVE_UINT64, waveforms.frame, path);
        write_attribute(f, "sample_interval_s", H5T_NATIVE_DOUBLE, r.sample_interval_s, path);
        write_attribute(f, "pulse_fwhm_s", H5T_NATIVE_DOUBLE, r.pulse_fwhm_s, path);
        write_attribute(f, "threshold_a", H5T_NATIVE_DOUBLE, r.threshold_a, path);
        write_attribute(f, "release_a", H5T_NATIVE_DOUBLE, r.release_a, path);
        write_attribute(f, "noise_floor_a", H5T_NATIVE_DOUBLE, r.noise_floor_a, path);
        write_attribute(f, "saturation_a", H5T_NATIVE_DOUBLE, r.saturation_a, path);
        write_attribute(f, "photoelectrons_per_coulomb", H5T_NATIVE_DOUBLE, r.photoelectrons_per_coulomb, path);
        write_text_attribute(f, "units", "samples: detector current, A; times: s (time_s on the frame's clock, start_s after the emission)",
                             path);
        check(H5Fflush(f, H5F_SCOPE_GLOBAL) >= 0, path, "flush");
    }
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        throw std::runtime_error(path.string() + ": cannot write the waveforms: " + ec.message());
    }
}

FrameWaveforms read_waveforms_h5(const std::filesystem::path& path) {
    const QuietHdf5 quiet;
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file.ok()) throw InputError(path.string(), "(file)", "cannot be opened as HDF5");
    const hid_t f = file.get();
    FrameWaveforms w;
    w.frame = read_attribute<std::uint64_t>(f, "frame", H5T_NATIVE_UINT64, path);
    WaveformReceiverInfo& r = w.receiver;
    r.sample_interval_s = read_attribute<double>(f, "sample_interval_s", H5T_NATIVE_DOUBLE, path);
    r.pulse_fwhm_s = read_attribute<double>(f, "pulse_fwhm_s", H5T_NATIVE_DOUBLE, path);
    r.threshold_a = read_attribute<double>(f, "threshold_a", H5T_NATIVE_DOUBLE, path);
    r.release_a = read_attribute<double>(f, "release_a", H5T_NATIVE_DOUBLE, path);
    r.noise_floor_a = read_attribute<double>(f, "noise_floor_a", H5T_NATIVE_DOUBLE, path);
    r.saturation_a = read_attribute<double>(f, "saturation_a", H5T_NATIVE_DOUBLE, path);
    r.photoelectrons_per_coulomb = read_attribute<double>(f, "photoelectrons_per_coulomb", H5T_NATIVE_DOUBLE, path);
    const auto column = read_column<std::uint16_t>(f, "column", H5T_NATIVE_UINT16, path);
    const auto row = read_column<std::uint16_t>(f, "row", H5T_NATIVE_UINT16, path);
    const auto time = read_column<double>(f, "time_s", H5T_NATIVE_DOUBLE, path);
    const auto start = read_column<double>(f, "start_s", H5T_NATIVE_DOUBLE, path);
    const auto first = read_column<std::uint64_t>(f, "first_sample", H5T_NATIVE_UINT64, path);
    const auto count = read_column<std::uint32_t>(f, "sample_count", H5T_NATIVE_UINT32, path);
    const auto samples = read_column<float>(f, "samples", H5T_NATIVE_FLOAT, path);
    const std::size_t n = column.size();
    if (row.size() != n || time.size() != n || start.size() != n || first.size() != n || count.size() != n)
        throw InputError(path.string(), "row", "the per-window datasets differ in length");
    for (std::size_t i = 0; i < n; ++i) {
        if (first[i] > samples.size() || count[i] > samples.size() - first[i])
            throw InputError(path.string(), "first_sample", "window " + std::to_string(i) + " reaches past /samples");
        w.windows.push_back({column[i], row[i], time[i], start[i],
                             std::vector<float>(samples.begin() + static_cast<std::ptrdiff_t>(first[i]),
                                                samples.begin() + static_cast<std::ptrdiff_t>(first[i] + count[i]))});
    }
    return w;
}

}  // namespace ladarsim
