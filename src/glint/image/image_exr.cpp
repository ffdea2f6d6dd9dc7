// OpenEXR files through OpenEXR itself (the reference implementation): ZIP-compressed float
// channels with string attributes on writing; R, G, B (or Y) of the first part on reading, as
// floats whatever their stored type.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <fmt/core.h>
#include <tbb/info.h>

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

}  // namespace

RawImage read_exr(const fs::path& path, long long max_pixels) {
    exr_threads();
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const auto [w, h] = window_size(dw);
        admit_image(path, w, h, max_pixels, 3 * 4 * 2, kExrPixelsPerByte);
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
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const auto [w, h] = window_size(dw);
        const Imf::ChannelList& channels = file.header().channels();
        ExrChannels out;
        for (auto c = channels.begin(); c != channels.end(); ++c) out.names.emplace_back(c.name());
        std::vector<std::size_t> present;
        for (std::size_t i = 0; i < wanted.size(); ++i)
            if (channels.findChannel(wanted[i])) present.push_back(i);
        admit_image(path, w, h, max_pixels, static_cast<int>(std::max<std::size_t>(1, present.size())) * 4, kExrPixelsPerByte);
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
