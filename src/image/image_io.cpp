#include "image/image_io.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "image/image_codec.h"

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

// The OpenImageIO module: $WAVEPATH_IMAGE_MODULE, else the build's.
const char* image_module_path() {
    const char* env = std::getenv("WAVEPATH_IMAGE_MODULE");
    return env && *env ? env : WAVEPATH_IMAGE_MODULE;
}

// The module, opened on the first call. Throws std::runtime_error naming it
// if it cannot be loaded.
const image_codec::Codec& codec() {
    static const image_codec::Codec* const loaded = [] {
        void* module = dlopen(image_module_path(), RTLD_NOW | RTLD_LOCAL);
        const char* error = module ? nullptr : dlerror();
        auto* entry =
            module ? reinterpret_cast<const image_codec::Codec* (*)()>(dlsym(module, "wavepath_image_codec")) : nullptr;
        if (!entry)  // dlerror names the module
            throw std::runtime_error(std::string("cannot load the image library: ") + (error ? error : dlerror()));
        return entry();
    }();
    return *loaded;
}

// Writes `image` to `file`, whose extension selects OpenImageIO's writer;
// errors name `target`, the path the user asked for.
void write_with_oiio(const Image& image, const Format& format, const fs::path& file, const std::string& target) {
    const bool srgb = format.encoding == Encoding::Srgb8;
    const std::vector<std::uint8_t> encoded = srgb ? encode_srgb8_values(image.rgb) : std::vector<std::uint8_t>{};
    const image_codec::Codec* writer = nullptr;
    try {
        writer = &codec();
    } catch (const std::runtime_error& error) {
        throw OutputError("cannot write " + target + ": " + error.what());
    }
    const std::string error =
        writer->write(file.string(), image.width, image.height, srgb,
                      srgb ? static_cast<const void*>(encoded.data()) : image.rgb.data(), format.compression);
    if (!error.empty()) throw OutputError("cannot write " + target + ": " + error);
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
    // A missing module fails here, before the render; loading it would cost
    // every process that fails later (a scene error) what the module saves.
    if (format_for(path).encoding != Encoding::Pfm && access(image_module_path(), R_OK) != 0)
        throw OutputError("cannot write " + path + ": cannot load the image library: " + image_module_path() + ": " +
                          std::strerror(errno));
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

namespace {

// A texture's image of what the codec read of a file (or of `bytes`, not null).
Image texture_image(const std::string& file, const std::string* bytes, TextureChannels channels, int max_side) {
    const bool alpha = channels == TextureChannels::Alpha;
    image_codec::Pixels pixels;
    const std::string error = codec().read(
        file, bytes, alpha ? image_codec::ReadChannels::Alpha : image_codec::ReadChannels::Colour, max_side, pixels);
    if (!error.empty()) throw std::runtime_error("cannot read the image: " + error);
    if (pixels.width > max_side || pixels.height > max_side) {
        throw std::runtime_error(std::to_string(pixels.width) + " x " + std::to_string(pixels.height) +
                                 " texels, more than " + std::to_string(max_side) + " on a side");
    }
    // Grey, with or without alpha, is read as its grey channel in all three (Mitsuba's bitmap
    // texture reads grey and alpha as grey); the codec gives min(channels, 3) a texel, or the alpha.
    const bool grey = alpha || pixels.channels <= 2;
    const std::size_t stride = alpha ? 1 : static_cast<std::size_t>(std::min(pixels.channels, 3));
    const bool decode = channels == TextureChannels::Colour && !pixels.floating_point;
    Image image;
    image.width = pixels.width;
    image.height = pixels.height;
    image.rgb.resize(static_cast<std::size_t>(pixels.width) * static_cast<std::size_t>(pixels.height) * 3);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        const float value = pixels.values[grey ? i / 3 * stride : i];
        image.rgb[i] = decode ? decode_srgb(value) : value;
    }
    return image;
}

}  // namespace

Image read_texture_image(const std::string& path, TextureChannels channels, int max_side) {
    if (std::FILE* file = std::fopen(path.c_str(), "rb")) {  // OpenImageIO would name the path; the caller does
        std::fclose(file);
    } else {
        throw std::runtime_error(std::string("cannot open: ") + std::strerror(errno));
    }
    return texture_image(path, nullptr, channels, max_side);
}

Image read_texture_image_bytes(const std::string& bytes, const std::string& format, TextureChannels channels,
                               int max_side) {
    return texture_image("embedded." + format, &bytes, channels, max_side);
}

Image read_image(const std::string& path) {
    image_codec::Pixels pixels;
    const std::string error =
        codec().read(path, nullptr, image_codec::ReadChannels::Colour, std::numeric_limits<int>::max(), pixels);
    if (!error.empty()) throw std::runtime_error("cannot read " + path + ": " + error);
    if (pixels.channels < 3) throw std::runtime_error("cannot read " + path + ": fewer than 3 channels");
    Image image;
    image.width = pixels.width;
    image.height = pixels.height;
    image.rgb = std::move(pixels.values);
    return image;
}

}  // namespace wp
