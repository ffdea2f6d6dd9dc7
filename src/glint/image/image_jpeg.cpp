// JPEG through libjpeg-turbo. libjpeg reports errors by calling error_exit, which must not
// return: it longjmps back here, where nothing with a destructor has been created since setjmp
// (the pixels live in a vector made before it).
#include <csetjmp>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <cerrno>
#include <memory>

#include <fmt/core.h>
#include <jpeglib.h>

#include "glint/image/image_formats.h"

namespace glint {

namespace {

struct ErrorManager {
    jpeg_error_mgr pub;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void on_error(j_common_ptr cinfo) {
    auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, err->message);
    std::longjmp(err->jump, 1);
}

void on_warning(j_common_ptr, int) {}  // corrupt-data warnings: decode what is there, as viewers do

}  // namespace

bool read_jpeg(const std::filesystem::path& path, long long max_pixels, RawImage& out) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw IoError(fmt::format("cannot read image '{}': {}", path.string(), std::strerror(errno)));
    jpeg_decompress_struct cinfo{};
    ErrorManager err{};
    cinfo.err = jpeg_std_error(&err.pub);
    err.pub.error_exit = on_error;
    err.pub.emit_message = on_warning;
    std::vector<unsigned char> pixels;
    std::string failure;  // the size or memory check's verdict (nothing may throw past libjpeg)
    bool cmyk = false;
    long long w = 0, h = 0;
    if (setjmp(err.jump) != 0) {
        jpeg_destroy_decompress(&cinfo);
        throw IoError(fmt::format("cannot read image '{}': {}", path.string(), err.message));
    }
    jpeg_create_decompress(&cinfo);
    jpeg_stdio_src(&cinfo, file.get());
    jpeg_read_header(&cinfo, TRUE);
    w = cinfo.image_width;
    h = cinfo.image_height;
    cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
    if (!cmyk) failure = image_admission_error(path, w, h, max_pixels, 3 * 4 + 3, kJpegPixelsPerByte);
    if (cmyk || !failure.empty()) {
        jpeg_destroy_decompress(&cinfo);
    } else {
        cinfo.out_color_space = JCS_RGB;  // greyscale is expanded by libjpeg-turbo
        pixels.resize(static_cast<std::size_t>(w * h) * 3);
        jpeg_start_decompress(&cinfo);
        while (cinfo.output_scanline < cinfo.output_height) {
            JSAMPROW row = &pixels[static_cast<std::size_t>(cinfo.output_scanline) * static_cast<std::size_t>(w) * 3];
            jpeg_read_scanlines(&cinfo, &row, 1);
        }
        jpeg_finish_decompress(&cinfo);
        jpeg_destroy_decompress(&cinfo);
    }
    if (cmyk) return false;
    if (!failure.empty()) throw IoError(failure);
    out.width = static_cast<int>(w);
    out.height = static_cast<int>(h);
    out.channels = 3;
    out.is_float = false;
    out.data.resize(pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) out.data[i] = static_cast<float>(pixels[i]) / 255.0f;
    return true;
}

std::vector<std::uint8_t> encode_jpeg(const std::uint8_t* rgb, int width, int height, const ImageMetadata& metadata,
                                      int quality) {
    // One COM marker of name=value lines (a marker holds at most 65,533 bytes).
    std::string comment;
    for (const auto& [name, value] : metadata) comment += name + "=" + value + "\n";
    if (comment.size() > 65533) comment.resize(65533);
    // What libjpeg's memory destination allocates (with malloc) lives outside the frame setjmp
    // saves, so that it is seen, and freed, after a longjmp.
    struct Output {
        unsigned char* buffer = nullptr;
        unsigned long size = 0;
        ~Output() { std::free(buffer); }
    } output;
    jpeg_compress_struct cinfo{};
    ErrorManager err{};
    cinfo.err = jpeg_std_error(&err.pub);
    err.pub.error_exit = on_error;
    if (setjmp(err.jump) != 0) {
        jpeg_destroy_compress(&cinfo);
        throw IoError(fmt::format("libjpeg: {}", err.message));
    }
    jpeg_create_compress(&cinfo);
    jpeg_mem_dest(&cinfo, &output.buffer, &output.size);
    cinfo.image_width = static_cast<JDIMENSION>(width);
    cinfo.image_height = static_cast<JDIMENSION>(height);
    cinfo.input_components = 3;
    cinfo.in_color_space = JCS_RGB;
    jpeg_set_defaults(&cinfo);
    jpeg_set_quality(&cinfo, quality, TRUE);
    for (int c = 0; c < 3; ++c) cinfo.comp_info[c].h_samp_factor = cinfo.comp_info[c].v_samp_factor = 1;
    jpeg_start_compress(&cinfo, TRUE);
    if (!comment.empty())
        jpeg_write_marker(&cinfo, JPEG_COM, reinterpret_cast<const JOCTET*>(comment.data()),
                          static_cast<unsigned>(comment.size()));
    const std::size_t row_bytes = static_cast<std::size_t>(width) * 3;
    while (cinfo.next_scanline < cinfo.image_height) {
        // libjpeg's rows are not const, but it only reads them.
        JSAMPROW row = const_cast<JSAMPROW>(rgb + static_cast<std::size_t>(cinfo.next_scanline) * row_bytes);
        jpeg_write_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_compress(&cinfo);
    jpeg_destroy_compress(&cinfo);
    return {output.buffer, output.buffer + output.size};
}

}  // namespace glint
