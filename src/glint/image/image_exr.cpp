// OpenEXR files through OpenEXR itself (the reference implementation): ZIP-compressed float
// channels with string attributes on writing; R, G, B (or Y) of the first part on reading, as
// floats whatever their stored type.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfVersion.h>
#include <fmt/core.h>
#include <tbb/info.h>

#include <cmath>
#include <fstream>
#include <mutex>
#include <utility>

#include "glint/image/image_formats.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// OpenEXR compresses and decompresses blocks on its own thread pool; one thread per core.
void exr_threads() {
    static std::once_flag once;
    std::call_once(once, [] { Imf::setGlobalThreadCount(std::max(1, tbb::info::default_concurrency())); });
}

// The data window's width and height, in 64 bits (a header may claim the whole int range).
std::pair<long long, long long> window_size(const Imath::Box2i& dw) {
    return {static_cast<long long>(dw.max.x) - dw.min.x + 1, static_cast<long long>(dw.max.y) - dw.min.y + 1};
}

// Scan lines per compressed block, by codec (OpenEXR's own table); 256 for a codec it lacks.
long long lines_per_block(Imf::Compression c) {
    switch (c) {
        case Imf::NO_COMPRESSION: case Imf::RLE_COMPRESSION: case Imf::ZIPS_COMPRESSION: return 1;
        case Imf::ZIP_COMPRESSION: case Imf::PXR24_COMPRESSION: return 16;
        case Imf::PIZ_COMPRESSION: case Imf::B44_COMPRESSION: case Imf::B44A_COMPRESSION: case Imf::DWAA_COMPRESSION: return 32;
        default: return 256;
    }
}

// The first part's header, read by OpenEXR's own parser but without opening the file for pixels:
// Imf::InputFile's constructor allocates its line (or tile) buffers from the header at once, so a
// header that lies is checked here first (admit_exr).
Imf::Header read_exr_header(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("cannot read image '{}': cannot open it", path.string()));
    char magic[4] = {};
    unsigned char v[4] = {};
    in.read(magic, 4);
    in.read(reinterpret_cast<char*>(v), 4);
    if (!in || !Imf::isImfMagic(magic))
        throw IoError(fmt::format("cannot read image '{}': it is not an OpenEXR file", path.string()));
    int version = static_cast<int>(v[0] | (v[1] << 8) | (v[2] << 16) | (static_cast<unsigned>(v[3]) << 24));
    if (Imf::getVersion(version) != Imf::EXR_VERSION || !Imf::supportsFlags(Imf::getFlags(version)))
        throw IoError(fmt::format("cannot read image '{}': OpenEXR version field {:#x} is not one glint reads", path.string(),
                                  static_cast<unsigned>(version)));
    Imf::StdIFStream stream(in, path.c_str());
    Imf::Header header;
    header.readFrom(stream, version);
    return header;
}

// admit_image for an OpenEXR header, and one check more: the reader's working buffers. OpenEXR
// decodes through 2 x threads buffers of one block each (16 to 256 scan lines or a tile, by codec)
// plus the decompressor's copies, allocated when the file is opened, however few rows the data
// window has: a 500-byte header claiming a window 8 million pixels wide and one row high asked for
// gigabytes. The buffers may take as much memory as the image, or 256 MB: a wide image with large
// blocks is decoded on fewer threads (down to one buffer), one whose single block exceeds that is
// refused. Returns the threads to open the file with.
int admit_exr(const fs::path& path, const Imf::Header& header, long long max_pixels, int bytes_per_pixel) {
    const auto [w, h] = window_size(header.dataWindow());
    admit_image(path, w, h, max_pixels, bytes_per_pixel, kExrPixelsPerByte);
    double line_bytes = 0;  // one row of every channel, as stored (doubles: a tile may claim 2^31 x 2^31)
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
        line_bytes += (c.channel().type == Imf::HALF ? 2.0 : 4.0) * (w / std::max(1, c.channel().xSampling) + 1);
    double block_bytes = line_bytes * static_cast<double>(lines_per_block(header.compression()));
    if (header.hasTileDescription()) {
        const Imf::TileDescription& t = header.tileDescription();
        block_bytes = line_bytes / static_cast<double>(w) * t.xSize * t.ySize;
    }
    const double per_buffer = 3.0 * block_bytes;  // the block, the compressed block, the codec's scratch
    const double allowed = std::max(static_cast<double>(w * h * bytes_per_pixel), 256.0 * (1 << 20));
    if (per_buffer > allowed)
        throw IoError(fmt::format("cannot read image '{}': its header claims a {} x {} data window in blocks of {}; OpenEXR "
                                  "would need {:.1f} MB of buffers to decode one, more than the image itself (or 256 MB)",
                                  path.string(), w, h,
                                  header.hasTileDescription()
                                      ? fmt::format("{} x {} tiles", header.tileDescription().xSize, header.tileDescription().ySize)
                                      : fmt::format("{} rows", lines_per_block(header.compression())),
                                  per_buffer / 1e6));
    // OpenEXR keeps 2 x threads buffers (one without threads).
    const double buffers = std::floor(allowed / per_buffer);
    return buffers >= 2 * Imf::globalThreadCount() ? Imf::globalThreadCount() : static_cast<int>(buffers / 2);
}

}  // namespace

RawImage read_exr(const fs::path& path, long long max_pixels) {
    exr_threads();
    try {
        const int threads = admit_exr(path, read_exr_header(path), max_pixels, 3 * 4 * 2);
        Imf::InputFile file(path.c_str(), threads);
        const Imath::Box2i dw = file.header().dataWindow();
        const auto [w, h] = window_size(dw);
        const Imf::ChannelList& channels = file.header().channels();
        std::vector<std::string> names;
        if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B")) {
            names = {"R", "G", "B"};
        } else if (channels.findChannel("Y")) {
            names = {"Y"};
        } else if (channels.begin() != channels.end()) {
            names = {channels.begin().name()};  // one channel of another name: grey
        } else {
            throw IoError(fmt::format("cannot read image '{}': it has no channels", path.string()));
        }
        RawImage raw;
        raw.width = static_cast<int>(w);
        raw.height = static_cast<int>(h);
        raw.channels = static_cast<int>(names.size());
        raw.is_float = true;
        raw.data.assign(static_cast<std::size_t>(w * h) * names.size(), 0.0f);
        Imf::FrameBuffer fb;
        const std::size_t xs = sizeof(float) * names.size(), ys = xs * static_cast<std::size_t>(w);
        // OpenEXR addresses pixels by their data-window coordinates: the base is offset so that
        // (min.x, min.y) lands on the first element.
        char* base = reinterpret_cast<char*>(raw.data.data()) - static_cast<std::ptrdiff_t>(dw.min.x) * static_cast<std::ptrdiff_t>(xs) -
                     static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(ys);
        for (std::size_t c = 0; c < names.size(); ++c)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        return raw;
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), e.what()));
    }
}

ExrChannels read_exr_planes(const fs::path& path, const std::vector<std::string>& wanted, long long max_pixels) {
    exr_threads();
    try {
        const Imf::Header header = read_exr_header(path);
        const Imf::ChannelList& channels = header.channels();
        ExrChannels out;
        for (auto c = channels.begin(); c != channels.end(); ++c) out.names.emplace_back(c.name());
        std::vector<std::size_t> present;
        for (std::size_t i = 0; i < wanted.size(); ++i)
            if (channels.findChannel(wanted[i])) present.push_back(i);
        const int threads = admit_exr(path, header, max_pixels, static_cast<int>(std::max<std::size_t>(1, present.size())) * 4);
        Imf::InputFile file(path.c_str(), threads);
        const Imath::Box2i dw = file.header().dataWindow();
        const auto [w, h] = window_size(dw);
        out.width = static_cast<int>(w), out.height = static_cast<int>(h);
        out.planes.resize(wanted.size());
        Imf::FrameBuffer fb;
        const std::size_t row = sizeof(float) * static_cast<std::size_t>(w);
        for (const std::size_t i : present) {
            out.planes[i].assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
            char* base = reinterpret_cast<char*>(out.planes[i].data()) -
                         static_cast<std::ptrdiff_t>(dw.min.x) * static_cast<std::ptrdiff_t>(sizeof(float)) -
                         static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(row);
            fb.insert(wanted[i], Imf::Slice(Imf::FLOAT, base, sizeof(float), row));
        }
        file.setFrameBuffer(fb);
        if (!present.empty()) file.readPixels(dw.min.y, dw.max.y);
        return out;
    } catch (const IoError&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), e.what()));
    }
}

void write_exr(const fs::path& path, int width, int height, const std::vector<std::string>& names,
               const float* data, const ImageMetadata& metadata) {
    exr_threads();
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const auto& [key, value] : metadata) header.insert(key, Imf::StringAttribute(value));
        Imf::FrameBuffer fb;
        const std::size_t xs = sizeof(float) * names.size(), ys = xs * static_cast<std::size_t>(width);
        for (std::size_t c = 0; c < names.size(); ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(data + c)), xs, ys));
        }
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(height);
    } catch (const std::exception& e) {
        throw IoError(e.what());  // the caller names the file
    }
}

}  // namespace glint
