#include "glint/image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>

#include "testing.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

using testing::read_file;

class ImageIo : public ::testing::Test {
protected:
    static Film sample_film() {
        Film film(3, 2);
        film.at(0, 0) = {0, 0.5f, 1};
        film.at(1, 0) = {2.5f, 0.1f, 0.25f};
        film.at(2, 1) = {1, 1, 1};
        return film;
    }
    std::size_t file_count() const { return dir_.file_count(); }
    testing::TempDir dir_;
};

TEST_F(ImageIo, PngRawRoundTripsThroughOpenImageIO) {
    const fs::path p = dir_ / "a.png";
    write_image(p, sample_film(), DisplaySettings{Encoding::kRaw});
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in);
    ASSERT_EQ(in->spec().width, 3);
    ASSERT_EQ(in->spec().height, 2);
    std::vector<unsigned char> px(3 * 2 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
    // Row 0 (top): (0, 0.5, 1) -> 0 128 255; (2.5, 0.1, 0.25) -> 255 26 64 (63.75 rounds up).
    EXPECT_EQ(px[0], 0);
    EXPECT_EQ(px[1], 128);
    EXPECT_EQ(px[2], 255);
    EXPECT_EQ(px[3], 255);
    EXPECT_EQ(px[4], 26);
    EXPECT_EQ(px[5], 64);
    EXPECT_EQ(px[15], 255);  // (2,1)
}

TEST_F(ImageIo, ExrIsLinearAndUnclamped) {
    const fs::path p = dir_ / "a.exr";
    write_image(p, sample_film(), DisplaySettings{Encoding::kRaw});
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in);
    std::vector<float> px(3 * 2 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
    EXPECT_EQ(px[3], 2.5f);
    EXPECT_EQ(px[4], 0.1f);
    EXPECT_EQ(px[1], 0.5f);
}

TEST_F(ImageIo, PpmIsWritten) {
    const fs::path p = dir_ / "a.ppm";
    write_image(p, sample_film(), DisplaySettings{});
    EXPECT_EQ(read_file(p).rfind("P6", 0), 0u);
}

TEST_F(ImageIo, UnsupportedExtensionIsRefusedAndNothingIsWritten) {
    EXPECT_THROW(write_image(dir_ / "a.gif", sample_film(), DisplaySettings{}), IoError);
    EXPECT_THROW(check_writable(dir_ / "noext"), IoError);
    EXPECT_EQ(file_count(), 0u);
}

TEST_F(ImageIo, MissingFolderIsRefused) {
    try {
        check_writable(dir_ / "nope" / "a.png");
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
    }
}

TEST_F(ImageIo, SuccessfulWriteReplacesTheFileAndLeavesNoTemporary) {
    const fs::path p = dir_ / "a.png";
    std::ofstream(p) << "old";
    write_image(p, sample_film(), DisplaySettings{});
    EXPECT_NE(read_file(p), "old");
    EXPECT_EQ(file_count(), 1u);
}

TEST_F(ImageIo, FailedWriteLeavesTheExistingTargetUntouched) {
    // The destination is a non-empty folder: the image is written to the temporary file, but
    // cannot be renamed over it. The folder and its content must survive, and no temporary
    // file may be left behind.
    const fs::path p = dir_ / "target.png";
    fs::create_directory(p);
    std::ofstream(p / "keep.txt") << "precious";
    EXPECT_THROW(write_image(p, sample_film(), DisplaySettings{}), IoError);
    EXPECT_EQ(read_file(p / "keep.txt"), "precious");
    EXPECT_EQ(file_count(), 1u);
}

}  // namespace
}  // namespace glint
