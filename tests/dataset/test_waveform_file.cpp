// Full-waveform files: what write_waveforms_h5 writes read back by read_waveforms_h5, the same
// bytes for the same waveforms, and files the reader refuses. (tests/python/test_waveforms.py
// reads them with h5py, independently.)
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/waveform_file.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;

namespace {

FrameWaveforms three_windows() {
    FrameWaveforms w;
    w.frame = 42;
    w.receiver = {0.125e-9, 1e-9, 2e-7, 1e-7, 4e-8, 1e-3, 6.2e18};
    w.windows = {{3, 0, 0.5, 1e-6, {0.0f, 1e-7f, 3e-7f, 1e-7f}},
                 {3, 0, 0.5, 2e-6, {}},
                 {7, 2, 0.6, 4e-7, std::vector<float>(100000, 2.5e-7f)}};  // beyond one compressed chunk
    return w;
}

std::string bytes_of(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("a waveform file reads back as the windows and receiver constants written", "[waveforms]") {
    test::ScratchDir dir;
    const FrameWaveforms written = three_windows();
    write_waveforms_h5(dir / "w.h5", written);
    CHECK(!std::filesystem::exists(dir / "w.h5.tmp"));
    const FrameWaveforms read = read_waveforms_h5(dir / "w.h5");
    CHECK(read.frame == 42);
    CHECK(read.receiver.sample_interval_s == written.receiver.sample_interval_s);
    CHECK(read.receiver.threshold_a == written.receiver.threshold_a);
    CHECK(read.receiver.release_a == written.receiver.release_a);
    CHECK(read.receiver.photoelectrons_per_coulomb == written.receiver.photoelectrons_per_coulomb);
    REQUIRE(read.windows.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
        CHECK(read.windows[i].column == written.windows[i].column);
        CHECK(read.windows[i].row == written.windows[i].row);
        CHECK(read.windows[i].time_s == written.windows[i].time_s);
        CHECK(read.windows[i].start_s == written.windows[i].start_s);
        CHECK(read.windows[i].samples_a == written.windows[i].samples_a);
    }
}

TEST_CASE("a waveform file is the same bytes each time the same waveforms are written", "[waveforms]") {
    test::ScratchDir dir;
    write_waveforms_h5(dir / "a.h5", three_windows());
    write_waveforms_h5(dir / "b.h5", three_windows());
    CHECK(bytes_of(dir / "a.h5") == bytes_of(dir / "b.h5"));
    write_waveforms_h5(dir / "empty.h5", FrameWaveforms{});
    CHECK(read_waveforms_h5(dir / "empty.h5").windows.empty());
}

TEST_CASE("read_waveforms_h5 refuses a file that is not HDF5 in one line naming it", "[waveforms]") {
    test::ScratchDir dir;
    std::ofstream(dir / "text.h5") << "not HDF5";
    const InputError e = test::input_error_of([&] { read_waveforms_h5(dir / "text.h5"); });
    CHECK(e.file() == (dir / "text.h5").string());
    CHECK(e.field() == "(file)");
}
