#include "ladarsim/dataset/exr_file.h"

#include <climits>
#include <exception>
#include <stdexcept>
#include <string>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {

namespace {

template <typename T>
Imf::Slice slice(Imf::PixelType type, std::vector<T>& plane, int columns) {
    return Imf::Slice(type, reinterpret_cast<char*>(plane.data()), sizeof(T), sizeof(T) * static_cast<std::size_t>(columns));
}

}  // namespace

RangeImage range_image_of(const Frame& frame) {
    if (frame.columns <= 0 || frame.rows <= 0) {
        throw std::invalid_argument("write_frame_exr: frame " + std::to_string(frame.index) + " has a " +
                                    std::to_string(frame.columns) + " x " + std::to_string(frame.rows) + " raster");
    }
    if (frame.index > static_cast<std::uint64_t>(INT_MAX)) {
        throw std::invalid_argument("write_frame_exr: frame index " + std::to_string(frame.index) +
                                    " does not fit the EXR int attribute");
    }
    RangeImage image;
    image.columns = frame.columns;
    image.rows = frame.rows;
    image.frame_index = frame.index;
    image.start_time_s = frame.start_time_s;
    image.end_time_s = frame.end_time_s;
    const std::size_t pixels = static_cast<std::size_t>(frame.columns) * static_cast<std::size_t>(frame.rows);
    image.range_m.assign(pixels, 0.0f);
    image.intensity.assign(pixels, 0.0f);
    image.object_id.assign(pixels, kNoReturnObjectId);
    image.strongest_range_m.assign(pixels, 0.0f);
    image.strongest_intensity.assign(pixels, 0.0f);
    std::vector<bool> seen(pixels, false);
    for (const auto& r : frame.returns) {
        if (r.column >= frame.columns || r.row >= frame.rows) {
            throw std::invalid_argument("write_frame_exr: return at column " + std::to_string(r.column) + ", row " +
                                        std::to_string(r.row) + " lies outside the frame's raster");
        }
        const std::size_t p = image.pixel(r.column, r.row);
        if (!seen[p] || r.intensity > image.strongest_intensity[p]) {
            image.strongest_range_m[p] = static_cast<float>(r.range_m);
            image.strongest_intensity[p] = r.intensity;
            seen[p] = true;
        }
        if (r.return_index != 0) continue;
        image.range_m[p] = static_cast<float>(r.range_m);
        image.intensity[p] = r.intensity;
        image.object_id[p] = r.object_id;
    }
    return image;
}

std::vector<RangeImageChannel> range_image_channels(const RangeImage& image) {
    return {{"Y", &image.range_m, nullptr},
            {"range_m", &image.range_m, nullptr},
            {"intensity", &image.intensity, nullptr},
            {"object_id", nullptr, &image.object_id},
            {"strongest_range_m", &image.strongest_range_m, nullptr},
            {"strongest_intensity", &image.strongest_intensity, nullptr}};
}

void write_frame_exr(const std::filesystem::path& path, const Frame& frame) {
    RangeImage image = range_image_of(frame);

    Imf::Header header(image.columns, image.rows);
    header.compression() = Imf::ZIP_COMPRESSION;
    // A frame's image is small: zlib's fastest level writes it in two thirds of the time of the
    // default level, for files 1 % larger.
    header.zipCompressionLevel() = 1;
    header.lineOrder() = Imf::INCREASING_Y;  // row 0 (the top raster line) is the top of the image
    header.insert("frame_index", Imf::IntAttribute(static_cast<int>(image.frame_index)));
    header.insert("start_time_s", Imf::DoubleAttribute(image.start_time_s));
    header.insert("end_time_s", Imf::DoubleAttribute(image.end_time_s));

    Imf::FrameBuffer buffer;
    for (const RangeImageChannel& channel : range_image_channels(image)) {
        // OpenEXR's slices take a mutable base pointer; writing only reads through it.
        if (channel.float_plane) {
            header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
            buffer.insert(channel.name, slice(Imf::FLOAT, const_cast<std::vector<float>&>(*channel.float_plane), image.columns));
        } else {
            header.channels().insert(channel.name, Imf::Channel(Imf::UINT));
            buffer.insert(channel.name, slice(Imf::UINT, const_cast<std::vector<std::uint32_t>&>(*channel.uint_plane), image.columns));
        }
    }

    AtomicFile out(path);
    {
        // The OutputFile writes its line-offset table when destroyed, so it must be gone before
        // the file is committed.
        Imf::StdOFStream stream(out.stream(), out.temporary_path().c_str());
        Imf::OutputFile exr(stream, header);
        exr.setFrameBuffer(buffer);
        exr.writePixels(image.rows);
    }
    out.commit();
}

RangeImage read_frame_exr(const std::filesystem::path& path) {
    const std::string file = path.string();
    try {
        Imf::InputFile exr(file.c_str());
        const Imf::Header& header = exr.header();
        const Imath::Box2i window = header.dataWindow();
        if (window.min.x != 0 || window.min.y != 0) {
            throw InputError(file, "dataWindow", "expected to start at pixel (0, 0)");
        }
        RangeImage image;
        image.columns = window.max.x + 1;
        image.rows = window.max.y + 1;
        const std::size_t pixels = static_cast<std::size_t>(image.columns) * static_cast<std::size_t>(image.rows);
        image.range_m.resize(pixels);
        image.intensity.resize(pixels);
        image.object_id.resize(pixels);
        image.strongest_range_m.assign(pixels, 0.0f);
        image.strongest_intensity.assign(pixels, 0.0f);

        const auto require_channel = [&](const char* name, Imf::PixelType type) {
            const Imf::Channel* channel = header.channels().findChannel(name);
            if (!channel) throw InputError(file, name, "the image has no such channel");
            if (channel->type != type) {
                throw InputError(file, name, type == Imf::UINT ? "expected a UINT channel" : "expected a FLOAT channel");
            }
        };
        require_channel("range_m", Imf::FLOAT);
        require_channel("intensity", Imf::FLOAT);
        require_channel("object_id", Imf::UINT);

        const auto* index = header.findTypedAttribute<Imf::IntAttribute>("frame_index");
        if (!index || index->value() < 0) throw InputError(file, "frame_index", "missing or negative");
        const auto* start = header.findTypedAttribute<Imf::DoubleAttribute>("start_time_s");
        if (!start) throw InputError(file, "start_time_s", "missing");
        const auto* end = header.findTypedAttribute<Imf::DoubleAttribute>("end_time_s");
        if (!end) throw InputError(file, "end_time_s", "missing");
        image.frame_index = static_cast<std::uint64_t>(index->value());
        image.start_time_s = start->value();
        image.end_time_s = end->value();

        Imf::FrameBuffer buffer;
        buffer.insert("range_m", slice(Imf::FLOAT, image.range_m, image.columns));
        buffer.insert("intensity", slice(Imf::FLOAT, image.intensity, image.columns));
        buffer.insert("object_id", slice(Imf::UINT, image.object_id, image.columns));
        // Absent from images written before they existed: left at 0.
        if (header.channels().findChannel("strongest_range_m"))
            buffer.insert("strongest_range_m", slice(Imf::FLOAT, image.strongest_range_m, image.columns));
        if (header.channels().findChannel("strongest_intensity"))
            buffer.insert("strongest_intensity", slice(Imf::FLOAT, image.strongest_intensity, image.columns));
        exr.setFrameBuffer(buffer);
        exr.readPixels(0, window.max.y);
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        // OpenEXR reports unreadable, truncated or non-EXR files through Iex exceptions.
        throw InputError(file, "(file)", std::string("not a readable EXR image: ") + e.what());
    }
}

}  // namespace ladarsim
