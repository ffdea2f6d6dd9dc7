#pragma once
// The image file formats glint reads and writes itself, each through the field's own library
// (libspng, OpenEXR, libjpeg-turbo, zlib) or directly (Radiance HDR, PFM, PPM); the long tail
// of texture formats goes to OpenImageIO in a module loaded only when needed (oiio_module.h).
// Internal to image_io.cpp and its tests.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "glint/image/image_io.h"

namespace glint {

/// Decoded pixels, top row first, `channels` floats per pixel: integer formats scaled to [0, 1]
/// (is_float false), floating-point ones as stored.
struct RawImage {
    int width = 0, height = 0, channels = 0;
    bool is_float = false;
    std::vector<float> data;
};

/// The most pixels one byte of a file can decode to, per format: what a header's size is checked
/// against before anything is allocated, so that a 56-byte file claiming 11000 x 11000 pixels is
/// refused at once. Deflate expands at most 1032:1 (PNG: 8 one-bit pixels a byte); a baseline or
/// progressive JPEG needs at least one bit per 8 x 8 block; EXR's codecs (ZIP, PIZ's Huffman runs)
/// stay far below 2^16; Radiance HDR rows are checked row by row instead (a repeat code expands
/// without bound), PFM and PNM by their exact sizes.
inline constexpr double kPngPixelsPerByte = 1032.0 * 8, kJpegPixelsPerByte = 8 * 64, kExrPixelsPerByte = 65536,
                        kAnyPixelsPerByte = 65536;

/// Called by every reader once it knows the size, before it allocates the pixels: throws IoError
/// if width x height exceeds `max_pixels`, is more than the file's bytes can hold at
/// `pixels_per_byte` (0: not checked) or the memory budget refuses `bytes_per_pixel` bytes a
/// pixel. (Defined in image_io.cpp.)
void admit_image(const std::filesystem::path& path, long long width, long long height, long long max_pixels,
                 int bytes_per_pixel, double pixels_per_byte);
/// The same check's message, or "" when the image is admitted (and its memory charged).
std::string image_admission_error(const std::filesystem::path& path, long long width, long long height,
                                  long long max_pixels, int bytes_per_pixel, double pixels_per_byte);

RawImage read_png(const std::filesystem::path& path, long long max_pixels);
RawImage read_exr(const std::filesystem::path& path, long long max_pixels);
/// read_exr_channels (image_io.h) without the checks of the header's bytes.
ExrChannels read_exr_planes(const std::filesystem::path& path, const std::vector<std::string>& wanted,
                            long long max_pixels);
/// Returns false (nothing read) for a JPEG libjpeg cannot convert to RGB (CMYK): the caller
/// offers it to OpenImageIO.
bool read_jpeg(const std::filesystem::path& path, long long max_pixels, RawImage& out);
RawImage read_hdr(const std::filesystem::path& path, long long max_pixels);
RawImage read_pfm(const std::filesystem::path& path, long long max_pixels);
RawImage read_pnm(const std::filesystem::path& path, long long max_pixels);
RawImage read_oiio(const std::filesystem::path& path, long long max_pixels);

/// How a PNG is compressed: zlib's level and strategy (Z_DEFAULT_STRATEGY 0, Z_FILTERED 1,
/// Z_RLE 3), and the scanline filter (0 none, 1 sub, 2 up, 3 average, 4 Paeth).
struct PngOptions {
    int level = 1;
    int strategy = 0;
    int filter = 1;
};

/// A whole PNG file (8-bit RGB, rows top first) with text chunks for `metadata` (tEXt, or iTXt
/// when a value is not ASCII) and the colour encoding (sRGB chunk, or gAMA 1.0 when `srgb` is
/// false). The rows are filtered and deflated in parallel in strips of about kPngStripBytes
/// (png_strip_rows: whole rows, by the width alone), each strip primed with the 32 KiB before it
/// (pigz's method), so the bytes do not depend on the number of threads.
inline constexpr std::size_t kPngStripBytes = 256 * 1024;
std::size_t png_strip_rows(int width);
/// `rows(y, out)` writes row y's width x 3 bytes to out; it is called from several threads, and
/// for some rows more than once.
using PngRows = std::function<void(int y, std::uint8_t* out)>;
std::vector<std::uint8_t> encode_png(const PngRows& rows, int width, int height, bool srgb,
                                     const ImageMetadata& metadata, const PngOptions& options = {});

/// encode_png in pieces, for encoding while the image is made: rows_ready(y0, y1) says rows
/// [y0, y1) are final (from any thread; each row once), and encodes, on the calling thread,
/// every strip that then has all the rows it reads (its own and the dictionary's, which lie in
/// the strip before it). finish() encodes whatever is left and returns encode_png's bytes: the
/// same file whatever the order rows came in, or whether they were announced at all.
class PngStrips {
public:
    PngStrips(PngRows rows, int width, int height, const PngOptions& options = {});
    void rows_ready(int y0, int y1);
    std::vector<std::uint8_t> finish(bool srgb, const ImageMetadata& metadata);
    std::size_t count() const { return count_; }

private:
    std::size_t end_row(std::size_t s) const;
    std::size_t first_row_read(std::size_t s) const;
    bool ready(std::size_t s) const;
    void try_encode(std::size_t s);
    void encode(std::size_t s);
    std::vector<std::uint8_t> assemble(bool srgb, const ImageMetadata& metadata) const;

    PngRows rows_;
    int width_, height_;
    PngOptions options_;
    std::size_t row_, line_, strip_rows_, count_;
    std::vector<std::vector<std::uint8_t>> parts_;
    std::vector<unsigned long> adlers_;
    std::vector<int> status_;
    std::vector<std::atomic<bool>> claimed_;  ///< encoded, or being encoded
    std::vector<std::atomic<int>> left_;      ///< rows of the strip not yet announced
};
std::vector<std::uint8_t> encode_png(const std::uint8_t* rgb, int width, int height, bool srgb,
                                     const ImageMetadata& metadata, const PngOptions& options = {});

/// 8-bit RGB (rows top first) as a baseline JPEG through libjpeg-turbo: `quality` (1-100),
/// no chroma subsampling (4:4:4: a render's edges are in its colours as much as its brightness),
/// and `metadata` as one COM marker of "name=value" lines. Throws IoError with libjpeg's reason.
std::vector<std::uint8_t> encode_jpeg(const std::uint8_t* rgb, int width, int height, const ImageMetadata& metadata,
                                      int quality = 95);

/// Linear RGB floats (interleaved, rows top first) as a Radiance HDR file: 32-bit RGBE, rows
/// run-length encoded (the "new" per-component encoding) when 8 <= width < 32768, flat
/// otherwise; resolution "-Y height +X width"; `metadata` as NAME=value header lines. A value
/// RGBE cannot hold is clamped: NaN and negatives to 0, anything above 1e38 to 1e38.
std::vector<std::uint8_t> encode_hdr(const float* rgb, int width, int height, const ImageMetadata& metadata);
/// The four RGBE bytes of one linear RGB value (Ward's encoding: the largest component's
/// exponent e, each mantissa as floor(c * 256 / 2^e), e + 128).
void rgbe_encode(float r, float g, float b, std::uint8_t out[4]);

/// Linear RGB floats (interleaved, rows top first) as a colour PFM: "PF", the size, scale -1
/// (little-endian), then the rows bottom to top, every float as it is (unclamped, NaN kept).
std::vector<std::uint8_t> encode_pfm(const float* rgb, int width, int height);

/// Writes `channels` named float channels (interleaved in `data`) as a ZIP-compressed OpenEXR
/// file, with `metadata` as string attributes. Throws IoError with OpenEXR's reason (the caller
/// names the file).
void write_exr(const std::filesystem::path& path, int width, int height, const std::vector<std::string>& names,
               const float* data, const ImageMetadata& metadata);

}  // namespace glint
