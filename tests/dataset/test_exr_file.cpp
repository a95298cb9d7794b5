// EXR range images: read back with OpenEXR's own API (channel list, attributes, hand-set pixels)
// and through read_frame_exr.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>

#include "ladarsim/dataset/exr_file.h"
#include "ladarsim/core/input_error.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using ladarsim::test::ScratchDir;

namespace {

Return beam_return(std::uint16_t column, std::uint16_t row, std::uint8_t index, double range_m, float intensity,
                   std::uint32_t object_id) {
    Return r;
    r.column = column;
    r.row = row;
    r.return_index = index;
    r.range_m = range_m;
    r.intensity = intensity;
    r.object_id = object_id;
    return r;
}

/// 5 x 3 beams; (3, 1) has two returns, (0, 0) a background return, (4, 2) the last pixel.
Frame sample_frame() {
    Frame frame;
    frame.index = 42;
    frame.start_time_s = 4.2;
    frame.end_time_s = 4.3;
    frame.columns = 5;
    frame.rows = 3;
    frame.returns = {
        beam_return(0, 0, 0, 850.25, 0.125f, 0),
        beam_return(3, 1, 0, 1000.5, 0.5f, 3),
        beam_return(3, 1, 1, 1020.75, 0.25f, 0),
        beam_return(4, 2, 0, 12.0, 2.0f, 0xFFFFFFFDu),
    };
    return frame;
}

/// One channel of the whole image through OpenEXR's API, row-major.
template <typename T>
std::vector<T> exr_channel(Imf::InputFile& exr, const char* name, Imf::PixelType type, int columns, int rows) {
    std::vector<T> plane(static_cast<std::size_t>(columns * rows));
    Imf::FrameBuffer buffer;
    buffer.insert(name, Imf::Slice(type, reinterpret_cast<char*>(plane.data()), sizeof(T), sizeof(T) * columns));
    exr.setFrameBuffer(buffer);
    exr.readPixels(0, rows - 1);
    return plane;
}

InputError error_of(const std::filesystem::path& path) {
    return test::input_error_of([&] { read_frame_exr(path); });
}

}  // namespace

TEST_CASE("OpenEXR reads our image: size, channels, compression, attributes", "[exr_file]") {
    const ScratchDir dir;
    write_frame_exr(dir / "f.exr", sample_frame());
    Imf::InputFile exr((dir / "f.exr").string().c_str());
    const Imf::Header& header = exr.header();
    CHECK(header.dataWindow().min.x == 0);
    CHECK(header.dataWindow().min.y == 0);
    CHECK(header.dataWindow().max.x == 4);
    CHECK(header.dataWindow().max.y == 2);
    CHECK(header.compression() == Imf::ZIP_COMPRESSION);

    std::vector<std::pair<std::string, Imf::PixelType>> channels;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
        channels.emplace_back(c.name(), c.channel().type);
    }
    // OpenEXR lists channels alphabetically.
    const std::vector<std::pair<std::string, Imf::PixelType>> expected = {
        {"Y", Imf::FLOAT},         {"intensity", Imf::FLOAT},           {"object_id", Imf::UINT},
        {"range_m", Imf::FLOAT},   {"strongest_intensity", Imf::FLOAT}, {"strongest_range_m", Imf::FLOAT}};
    CHECK(channels == expected);

    const auto* index = header.findTypedAttribute<Imf::IntAttribute>("frame_index");
    REQUIRE(index);
    CHECK(index->value() == 42);
    const auto* start = header.findTypedAttribute<Imf::DoubleAttribute>("start_time_s");
    REQUIRE(start);
    CHECK(start->value() == 4.2);
    const auto* end = header.findTypedAttribute<Imf::DoubleAttribute>("end_time_s");
    REQUIRE(end);
    CHECK(end->value() == 4.3);
}

TEST_CASE("OpenEXR reads the hand-set pixels: first returns, no-return pixels 0 / 0xFFFFFFFE (a false alarm is 0xFFFFFFFF)", "[exr_file]") {
    const ScratchDir dir;
    write_frame_exr(dir / "f.exr", sample_frame());
    Imf::InputFile exr((dir / "f.exr").string().c_str());
    const auto range = exr_channel<float>(exr, "range_m", Imf::FLOAT, 5, 3);
    const auto y = exr_channel<float>(exr, "Y", Imf::FLOAT, 5, 3);
    const auto intensity = exr_channel<float>(exr, "intensity", Imf::FLOAT, 5, 3);
    const auto ids = exr_channel<std::uint32_t>(exr, "object_id", Imf::UINT, 5, 3);

    // Pixel (x, y) = (column, row) sits at y * 5 + x.
    const int p31 = 1 * 5 + 3;
    CHECK(range[p31] == 1000.5f);  // return 0, not the farther return 1 at 1020.75 m
    CHECK(intensity[p31] == 0.5f);
    CHECK(ids[p31] == 3);
    CHECK(range[0] == 850.25f);
    CHECK(ids[0] == 0);
    CHECK(range[14] == 12.0f);
    CHECK(intensity[14] == 2.0f);
    CHECK(ids[14] == 0xFFFFFFFDu);
    CHECK(y == range);
    for (int p : {1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 13}) {
        INFO("pixel " << p);
        CHECK(range[p] == 0.0f);
        CHECK(intensity[p] == 0.0f);
        CHECK(ids[p] == 0xFFFFFFFEu);
    }
}

TEST_CASE("round trip through read_frame_exr is exact", "[exr_file]") {
    const ScratchDir dir;
    write_frame_exr(dir / "f.exr", sample_frame());
    const RangeImage image = read_frame_exr(dir / "f.exr");
    CHECK(image.columns == 5);
    CHECK(image.rows == 3);
    CHECK(image.frame_index == 42);
    CHECK(image.start_time_s == 4.2);
    CHECK(image.end_time_s == 4.3);
    std::vector<float> range(15, 0.0f), intensity(15, 0.0f);
    std::vector<std::uint32_t> ids(15, kNoReturnObjectId);
    range[0] = 850.25f;
    intensity[0] = 0.125f;
    ids[0] = 0;
    range[image.pixel(3, 1)] = 1000.5f;
    intensity[image.pixel(3, 1)] = 0.5f;
    ids[image.pixel(3, 1)] = 3;
    range[14] = 12.0f;
    intensity[14] = 2.0f;
    ids[14] = 0xFFFFFFFDu;
    CHECK(image.range_m == range);
    CHECK(image.intensity == intensity);
    CHECK(image.object_id == ids);
    CHECK_FALSE(std::filesystem::exists(dir / "f.exr.tmp"));
}

TEST_CASE("the same frame gives the same bytes: no time stamps, deterministic compression", "[exr_file]") {
    const ScratchDir dir;
    write_frame_exr(dir / "a.exr", sample_frame());
    write_frame_exr(dir / "b.exr", sample_frame());
    std::ifstream a(dir / "a.exr", std::ios::binary), b(dir / "b.exr", std::ios::binary);
    CHECK(std::string(std::istreambuf_iterator<char>(a), {}) == std::string(std::istreambuf_iterator<char>(b), {}));
}

TEST_CASE("a frame without a raster, or a return outside it, is refused and nothing is written", "[exr_file]") {
    const ScratchDir dir;
    Frame no_raster;
    CHECK_THROWS_AS(write_frame_exr(dir / "a.exr", no_raster), std::invalid_argument);
    Frame outside = sample_frame();
    outside.returns.push_back(beam_return(5, 0, 0, 10.0, 1.0f, 0));
    CHECK_THROWS_AS(write_frame_exr(dir / "b.exr", outside), std::invalid_argument);
    CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("an EXR without object_id: InputError naming the channel", "[exr_file]") {
    const ScratchDir dir;
    const auto path = dir / "other.exr";
    {
        Imf::Header header(2, 2);
        header.channels().insert("range_m", Imf::Channel(Imf::FLOAT));
        header.channels().insert("intensity", Imf::Channel(Imf::FLOAT));
        std::vector<float> plane(4, 1.0f);
        Imf::FrameBuffer buffer;
        for (const char* name : {"range_m", "intensity"}) {
            buffer.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(plane.data()), sizeof(float),
                                           2 * sizeof(float)));
        }
        Imf::OutputFile exr(path.string().c_str(), header);
        exr.setFrameBuffer(buffer);
        exr.writePixels(2);
    }
    const InputError e = error_of(path);
    CHECK(e.file() == path.string());
    CHECK(e.field() == "object_id");
}

TEST_CASE("not an EXR, or a truncated one: InputError naming the file", "[exr_file]") {
    const ScratchDir dir;
    std::ofstream(dir / "text.exr") << "not an image";
    CHECK(error_of(dir / "text.exr").field() == "(file)");

    write_frame_exr(dir / "f.exr", sample_frame());
    std::filesystem::resize_file(dir / "f.exr", std::filesystem::file_size(dir / "f.exr") / 2);
    const InputError e = error_of(dir / "f.exr");
    CHECK(e.file() == (dir / "f.exr").string());
}

TEST_CASE("the strongest return's range and intensity: their own channels, the first return's when it is the strongest", "[exr_file]") {
    const ScratchDir dir;
    Frame frame = sample_frame();
    frame.returns.push_back(beam_return(1, 0, 0, 30.0, 0.5f, 7));
    frame.returns.push_back(beam_return(1, 0, 1, 95.0, 4.0f, 8));  // a later, brighter return
    write_frame_exr(dir / "f.exr", frame);
    const RangeImage image = read_frame_exr(dir / "f.exr");
    CHECK(image.range_m[image.pixel(1, 0)] == 30.0f);
    CHECK(image.object_id[image.pixel(1, 0)] == 7u);
    CHECK(image.strongest_range_m[image.pixel(1, 0)] == 95.0f);
    CHECK(image.strongest_intensity[image.pixel(1, 0)] == 4.0f);
    CHECK(image.strongest_range_m[image.pixel(3, 1)] == 1000.5f);  // first and strongest
    CHECK(image.strongest_intensity[image.pixel(3, 1)] == 0.5f);
    CHECK(image.strongest_range_m[image.pixel(2, 2)] == 0.0f);     // no return
    CHECK(image.object_id[image.pixel(2, 2)] == kNoReturnObjectId);
    CHECK(kNoReturnObjectId != kNoObject);
}
