// Image files: exact float round trips, the sRGB encoding of 8-bit formats,
// and atomic writing (no file, or the old file, whenever a write fails).
#include "image/image_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/atomic_file.h"

namespace wp {
namespace {

namespace fs = std::filesystem;

class ImageIoTest : public ::testing::Test {
 protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        directory_ = fs::temp_directory_path() / ("wavepath-image-" + std::to_string(::getpid()) + "-" + info->name());
        fs::remove_all(directory_);
        fs::create_directories(directory_);
    }
    void TearDown() override { fs::remove_all(directory_); }

    std::string path(const std::string& name) const { return (directory_ / name).string(); }

    // Names of every entry in the test directory, temporaries included.
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(directory_)) names.push_back(entry.path().filename());
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path directory_;
};

// Values that a lossy or half-float path would change: non-dyadic fractions,
// tiny and large magnitudes, and different values per channel and pixel.
Image gradient_image(int width, int height) {
    Image image{width, height, std::vector<float>(static_cast<std::size_t>(width * height * 3))};
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
        image.rgb[i] = static_cast<float>(std::pow(1.37, static_cast<double>(i % 40) - 20.0)) / 3.0f;
    return image;
}

void expect_same_pixels(const Image& expected, const Image& actual) {
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    ASSERT_EQ(actual.rgb.size(), expected.rgb.size());
    for (std::size_t i = 0; i < expected.rgb.size(); ++i) EXPECT_EQ(actual.rgb[i], expected.rgb[i]) << "value " << i;
}

TEST_F(ImageIoTest, ExrRoundTripIsExact) {
    const Image image = gradient_image(7, 5);
    write_image(image, path("a.exr"));
    expect_same_pixels(image, read_image(path("a.exr")));
}

TEST_F(ImageIoTest, PfmRoundTripIsExactAndKeepsTopRowFirst) {
    const Image image = gradient_image(4, 6);  // rows differ, so a vertical flip would show
    write_image(image, path("a.pfm"));
    expect_same_pixels(image, read_image(path("a.pfm")));
}

TEST_F(ImageIoTest, HdrRoundTripIsWithinRgbePrecision) {
    // RGBE keeps an 8-bit mantissa per channel relative to the largest channel.
    Image image{1, 2, {0.25f, 0.5f, 1.0f, 3.0f, 2.0f, 1.0f}};
    write_image(image, path("a.hdr"));
    const Image back = read_image(path("a.hdr"));
    ASSERT_EQ(back.rgb.size(), image.rgb.size());
    for (std::size_t i = 0; i < image.rgb.size(); ++i) EXPECT_NEAR(back.rgb[i], image.rgb[i], image.rgb[i] / 64.0f);
}

TEST_F(ImageIoTest, Srgb8EncodingOfKnownValues) {
    EXPECT_EQ(encode_srgb8(0.0f), 0);
    EXPECT_EQ(encode_srgb8(1.0f), 255);
    EXPECT_EQ(encode_srgb8(0.5f), 188);   // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
    EXPECT_EQ(encode_srgb8(0.002f), 7);   // linear segment: 12.92 * 0.002 * 255 = 6.59 -> 7
    EXPECT_EQ(encode_srgb8(0.18f), 118);  // 0.4614 * 255 = 117.7 -> 118 (a plain 2.2 gamma gives 117)
    EXPECT_EQ(encode_srgb8(-3.0f), 0);    // clamped
    EXPECT_EQ(encode_srgb8(40.0f), 255);  // clamped
}

TEST_F(ImageIoTest, PngStoresSrgbEncodedBytes) {
    const Image image{4, 1, {0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 0.5f, 0.5f, 0.5f, 0.18f, 7.0f, -1.0f}};
    write_image(image, path("a.png"));
    const Image back = read_image(path("a.png"));  // 8-bit code / 255
    const int expected[] = {0, 0, 0, 255, 255, 255, 188, 188, 188, 118, 255, 0};
    ASSERT_EQ(back.rgb.size(), std::size(expected));
    for (std::size_t i = 0; i < back.rgb.size(); ++i)
        EXPECT_EQ(std::lround(back.rgb[i] * 255.0f), expected[i]) << "value " << i;
}

TEST_F(ImageIoTest, JpgIsWrittenAndReadable) {
    const Image image{8, 8, std::vector<float>(8 * 8 * 3, 0.5f)};
    write_image(image, path("a.jpg"));
    const Image back = read_image(path("a.jpg"));
    ASSERT_EQ(back.rgb.size(), image.rgb.size());
    for (float v : back.rgb) EXPECT_NEAR(v * 255.0f, 188.0f, 2.0f);  // flat colour survives JPEG within 2 codes
}

TEST_F(ImageIoTest, WriteReplacesAnExistingFileAndLeavesNoTemporary) {
    write_image(gradient_image(2, 2), path("a.exr"));
    const Image second{2, 2, std::vector<float>(12, 0.25f)};
    write_image(second, path("a.exr"));
    expect_same_pixels(second, read_image(path("a.exr")));
    EXPECT_EQ(entries(), std::vector<std::string>{"a.exr"});
}

TEST_F(ImageIoTest, UnknownExtensionIsRejectedBeforeAnythingIsWritten) {
    EXPECT_THROW(validate_output_path(path("a.tga")), OutputError);
    EXPECT_THROW(validate_output_path(path("noextension")), OutputError);
    EXPECT_THROW(write_image(gradient_image(2, 2), path("a.bmp")), OutputError);
    EXPECT_TRUE(entries().empty());
    try {
        validate_output_path(path("a.tga"));
    } catch (const OutputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("a.tga"), std::string::npos) << message;
        EXPECT_NE(message.find(".png"), std::string::npos) << message;  // lists what is supported
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST_F(ImageIoTest, ExtensionMatchIgnoresCase) {
    EXPECT_NO_THROW(validate_output_path(path("A.PNG")));
    write_image(gradient_image(2, 2), path("A.EXR"));
    EXPECT_EQ(entries(), std::vector<std::string>{"A.EXR"});
}

TEST_F(ImageIoTest, MissingDirectoryIsRejectedAndNothingIsCreated) {
    const std::string target = path("missing/a.png");
    EXPECT_THROW(validate_output_path(target), OutputError);
    EXPECT_THROW(write_image(gradient_image(2, 2), target), OutputError);
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIoTest, DirectoryAsTargetIsRejected) {
    fs::create_directory(path("dir.png"));
    EXPECT_THROW(validate_output_path(path("dir.png")), OutputError);
}

TEST_F(ImageIoTest, NonFiniteValueIsRefusedAndExistingFileKept) {
    const Image original = gradient_image(3, 3);
    write_image(original, path("a.exr"));
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        Image broken = gradient_image(3, 3);
        broken.rgb[3 * 4 + 1] = bad;
        EXPECT_THROW(write_image(broken, path("a.exr")), std::invalid_argument);
    }
    expect_same_pixels(original, read_image(path("a.exr")));
    EXPECT_EQ(entries(), std::vector<std::string>{"a.exr"});
}

TEST_F(ImageIoTest, MalformedImageIsRefused) {
    EXPECT_THROW(write_image(Image{2, 2, std::vector<float>(11, 0.0f)}, path("a.exr")), std::invalid_argument);
    EXPECT_THROW(write_image(Image{0, 2, {}}, path("a.exr")), std::invalid_argument);
    EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIoTest, FailedWriterLeavesNoTemporaryAndKeepsExistingFile) {
    const std::string target = path("b.txt");
    std::ofstream(target) << "old";
    EXPECT_THROW(write_atomically(target,
                                  [](const fs::path& temporary) {
                                      std::ofstream(temporary) << "half";
                                      throw OutputError("disk full");
                                  }),
                 OutputError);
    EXPECT_EQ(entries(), std::vector<std::string>{"b.txt"});
    std::ifstream in(target);
    std::string content;
    in >> content;
    EXPECT_EQ(content, "old");
}

TEST_F(ImageIoTest, TemporaryKeepsTheExtensionAndIsHidden) {
    const fs::path temporary = temporary_path_for(directory_ / "room.png");
    EXPECT_EQ(temporary.parent_path(), directory_);
    EXPECT_EQ(temporary.extension(), ".png");
    EXPECT_EQ(temporary.filename().string().rfind(".room.png.tmp-", 0), 0u) << temporary;
}

TEST_F(ImageIoTest, ReadingAMissingFileThrows) { EXPECT_THROW(read_image(path("none.exr")), std::runtime_error); }

// Mitsuba 3.9.1's bitmap texture of a 1 x 1 8-bit RGB image (128, 64, 255)
// evaluates to (0.21586, 0.0512694, 1): the sRGB decode wavepath must match.
TEST_F(ImageIoTest, SrgbDecodeAsMitsuba) {
    EXPECT_NEAR(decode_srgb(128.0f / 255.0f), 0.21586f, 2e-6f);
    EXPECT_NEAR(decode_srgb(64.0f / 255.0f), 0.0512694f, 2e-7f);
    EXPECT_EQ(decode_srgb(0.0f), 0.0f);
    EXPECT_EQ(decode_srgb(1.0f), 1.0f);
    EXPECT_FLOAT_EQ(decode_srgb(10.0f / 255.0f), 10.0f / 255.0f / 12.92f);  // the linear segment
    for (int code = 0; code < 256; ++code)  // the inverse of the encoding, to the 8-bit code
        EXPECT_EQ(encode_srgb8(decode_srgb(code / 255.0f)), code) << code;
}

// A PNG texture is decoded from sRGB, unless raw; its rows stay top first.
TEST_F(ImageIoTest, TextureImagesDecodeEightBitFilesUnlessRaw) {
    const Image image{1, 2, {0.5f, 0.0f, 1.0f, 0.18f, 0.18f, 0.18f}};
    write_image(image, path("t.png"));  // codes 188, 0, 255 and 118
    const Image decoded = read_texture_image(path("t.png"), TextureChannels::Colour, 16);
    const Image raw = read_texture_image(path("t.png"), TextureChannels::Raw, 16);
    ASSERT_EQ(decoded.width, 1);
    ASSERT_EQ(decoded.height, 2);
    EXPECT_NEAR(decoded.rgb[0], 0.5f, 3e-3f);  // within the 8-bit code's step
    EXPECT_EQ(decoded.rgb[1], 0.0f);
    EXPECT_EQ(decoded.rgb[2], 1.0f);
    EXPECT_NEAR(decoded.rgb[3], 0.18f, 2e-3f);
    EXPECT_FLOAT_EQ(raw.rgb[0], 188.0f / 255.0f);
    EXPECT_FLOAT_EQ(raw.rgb[3], 118.0f / 255.0f);
    write_image(image, path("t.exr"));  // float files are linear already
    EXPECT_EQ(read_texture_image(path("t.exr"), TextureChannels::Colour, 16).rgb, image.rgb);
    EXPECT_THROW(read_texture_image(path("t.png"), TextureChannels::Colour, 1),
                 std::runtime_error);  // 2 rows, at most 1 allowed
}

// A grey texture with alpha (tests/image/grey_alpha.png: grey 200 and 50,
// alpha 10 and 255) is read as its grey, in all three channels, as Mitsuba's
// bitmap reads one: the alpha is not a colour (nor multiplied into it, as
// OpenImageIO does to PNG files unless told not to).
TEST_F(ImageIoTest, GreyAndAlphaTexturesAreReadAsTheirGrey) {
    const Image raw = read_texture_image(WAVEPATH_SOURCE_DIR "/tests/image/grey_alpha.png", TextureChannels::Raw, 16);
    ASSERT_EQ(raw.width, 2);
    ASSERT_EQ(raw.height, 1);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(raw.rgb[std::size_t(c)], 200.0f / 255.0f);
        EXPECT_FLOAT_EQ(raw.rgb[std::size_t(3 + c)], 50.0f / 255.0f);
    }
}

// Its alpha, read as TextureChannels::Alpha, is the stored alpha in all
// three channels (10 and 255 there); an image without alpha reads as 1.
TEST_F(ImageIoTest, TextureAlphaIsTheAlphaChannelOrOne) {
    const Image alpha =
        read_texture_image(WAVEPATH_SOURCE_DIR "/tests/image/grey_alpha.png", TextureChannels::Alpha, 16);
    ASSERT_EQ(alpha.rgb.size(), 6u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(alpha.rgb[std::size_t(c)], 10.0f / 255.0f);
        EXPECT_FLOAT_EQ(alpha.rgb[std::size_t(3 + c)], 1.0f);
    }
    write_image(Image{1, 2, {0.5f, 0.0f, 1.0f, 0.18f, 0.18f, 0.18f}}, path("t.png"));
    EXPECT_EQ(read_texture_image(path("t.png"), TextureChannels::Alpha, 16).rgb, std::vector<float>(6, 1.0f));
}

}  // namespace
}  // namespace wp
