#include "image/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"

namespace wp {

namespace fs = std::filesystem;

namespace {

// OpenImageIO 2.4 reads PFM but its PNM writer only writes 8/16-bit PPM,
// so PFM (a three-line header and raw floats) is written here.
enum class Encoding { LinearFloat, Srgb8, Pfm };

struct Format {
    const char* extension;
    Encoding encoding;
    const char* compression;  // OpenImageIO "compression" attribute, or nullptr for the default
};

constexpr std::array<Format, 6> kFormats{{
    {".exr", Encoding::LinearFloat, "zip"},  // lossless
    {".pfm", Encoding::Pfm, nullptr},
    {".hdr", Encoding::LinearFloat, nullptr},
    {".png", Encoding::Srgb8, nullptr},
    {".jpg", Encoding::Srgb8, "jpeg:95"},
    {".jpeg", Encoding::Srgb8, "jpeg:95"},
}};

std::string lowercase_extension(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

// The format for `path`; throws OutputError naming the supported extensions.
const Format& format_for(const std::string& path) {
    const std::string extension = lowercase_extension(path);
    for (const Format& format : kFormats)
        if (extension == format.extension) return format;
    std::string supported;
    for (const Format& format : kFormats) supported += std::string(supported.empty() ? "" : ", ") + format.extension;
    throw OutputError("cannot write " + path + ": unsupported image extension '" + extension + "' (use one of " +
                      supported + ")");
}

void check_image(const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3)
        throw std::invalid_argument("malformed image: " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " with " + std::to_string(image.rgb.size()) +
                                    " values");
    const auto bad = std::find_if(image.rgb.begin(), image.rgb.end(), [](float v) { return !std::isfinite(v); });
    if (bad != image.rgb.end()) {
        const std::size_t pixel = static_cast<std::size_t>(bad - image.rgb.begin()) / 3;
        throw std::invalid_argument("image has a non-finite value at pixel (" +
                                    std::to_string(pixel % static_cast<std::size_t>(image.width)) + ", " +
                                    std::to_string(pixel / static_cast<std::size_t>(image.width)) + ")");
    }
}

std::vector<std::uint8_t> encode_srgb8_values(const std::vector<float>& linear) {
    std::vector<std::uint8_t> encoded(linear.size());
    std::transform(linear.begin(), linear.end(), encoded.begin(), [](float v) { return encode_srgb8(v); });
    return encoded;
}

[[noreturn]] void fail_write(const std::string& target, const std::string& oiio_error) {
    throw OutputError("cannot write " + target + ": " +
                      (oiio_error.empty() ? std::string("unknown OpenImageIO error") : oiio_error));
}

// Writes `image` to `file`, whose extension selects OpenImageIO's writer;
// errors name `target`, the path the user asked for.
void write_with_oiio(const Image& image, const Format& format, const fs::path& file, const std::string& target) {
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(file.string());
    if (!output) fail_write(target, OIIO::geterror());

    const bool srgb = format.encoding == Encoding::Srgb8;
    const OIIO::TypeDesc type = srgb ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(image.width, image.height, 3, type);
    spec.attribute("oiio:ColorSpace", srgb ? "sRGB" : "Linear");
    if (format.compression) spec.attribute("compression", format.compression);

    if (!output->open(file.string(), spec)) fail_write(target, output->geterror());
    const bool written = srgb ? output->write_image(type, encode_srgb8_values(image.rgb).data())
                              : output->write_image(type, image.rgb.data());
    if (!written) fail_write(target, output->geterror());
    if (!output->close()) fail_write(target, output->geterror());
}

// PFM: "PF", width and height, a scale whose sign gives the byte order
// (negative: little-endian), then float RGB rows from the bottom row up.
void write_pfm(const Image& image, const fs::path& file, const std::string& target) {
    std::ofstream out(file, std::ios::binary);
    out << "PF\n"
        << image.width << ' ' << image.height << '\n'
        << (std::endian::native == std::endian::little ? "-1.0" : "1.0") << '\n';
    const std::size_t row_values = static_cast<std::size_t>(image.width) * 3;
    for (int row = image.height - 1; row >= 0; --row)
        out.write(reinterpret_cast<const char*>(image.rgb.data() + static_cast<std::size_t>(row) * row_values),
                  static_cast<std::streamsize>(row_values * sizeof(float)));
    out.close();
    if (!out) throw OutputError("cannot write " + target + ": " + std::strerror(errno));
}

}  // namespace

std::uint8_t encode_srgb8(float linear) {
    const double c = std::clamp(static_cast<double>(linear), 0.0, 1.0);
    const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

void validate_output_path(const std::string& path) {
    format_for(path);
    check_writable_destination(path);
}

void write_image(const Image& image, const std::string& path) {
    const Format& format = format_for(path);
    check_image(image);
    check_writable_destination(path);
    write_atomically(path, [&](const fs::path& temporary) {
        if (format.encoding == Encoding::Pfm)
            write_pfm(image, temporary, path);
        else
            write_with_oiio(image, format, temporary, path);
    });
}

float decode_srgb(float encoded) {
    double v = encoded;
    return static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

Image read_texture_image(const std::string& path, bool raw, int max_side) {
    if (std::FILE* file = std::fopen(path.c_str(), "rb")) {  // OpenImageIO would name the path; the caller does
        std::fclose(file);
    } else {
        throw std::runtime_error(std::string("cannot open: ") + std::strerror(errno));
    }
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw std::runtime_error("cannot read the image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.nchannels == 2) throw std::runtime_error("2 channels (grey and alpha): give grey, RGB or RGBA");
    if (spec.width > max_side || spec.height > max_side) {
        throw std::runtime_error(std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                                 " texels, more than " + std::to_string(max_side) + " on a side");
    }
    const int channels = std::min(spec.nchannels, 3);
    const std::size_t texels = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
    std::vector<float> stored(texels * static_cast<std::size_t>(channels));
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, stored.data()))
        throw std::runtime_error("cannot read the image: " + input->geterror());
    const bool decode = !raw && !spec.format.is_floating_point();
    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.rgb.resize(texels * 3);
    for (std::size_t i = 0; i < texels * 3; ++i) {
        const float value = stored[channels == 1 ? i / 3 : i];
        image.rgb[i] = decode ? decode_srgb(value) : value;
    }
    return image;
}

Image read_image(const std::string& path) {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw std::runtime_error("cannot read " + path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.nchannels < 3) throw std::runtime_error("cannot read " + path + ": fewer than 3 channels");
    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.rgb.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) * 3);
    if (!input->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, image.rgb.data()))
        throw std::runtime_error("cannot read " + path + ": " + input->geterror());
    return image;
}

}  // namespace wp
