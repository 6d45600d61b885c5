// Image files through OpenImageIO, the format chosen by the file extension:
// .exr, .pfm and .hdr hold linear float RGB; .png and .jpg/.jpeg hold
// sRGB-encoded 8-bit RGB, clamped to [0, 1] first.
#pragma once

#include <cstdint>
#include <string>

#include "core/render.h"

namespace wp {

// Throws OutputError unless `path` has a supported extension and its
// directory exists and is writable. The CLI calls it before rendering so
// that a bad output path fails in a second, not after the render.
void validate_output_path(const std::string& path);

// Writes atomically (temporary file, then rename): on failure nothing is left
// behind and an existing file at `path` is untouched. Throws OutputError for
// anything that prevents writing, std::invalid_argument for an image that is
// malformed or holds a non-finite value.
void write_image(const Image& image, const std::string& path);

// Any format OpenImageIO reads, as linear RGB floats exactly as stored (8-bit
// files are not decoded from sRGB: value / 255). Throws std::runtime_error.
Image read_image(const std::string& path);

// A texture's image as linear RGB floats, row 0 the file's top row: files
// of integer samples (PNG, JPEG: sRGB-encoded) are decoded from sRGB
// unless read Raw, as Mitsuba 3's bitmap does; float files (EXR, HDR) are read
// as stored. Grey, with or without alpha, is copied to all three channels;
// beyond three, the rest (alpha) is left out. Throws std::runtime_error (the
// file unreadable, a side over `max_side`).
// With TextureChannels::Alpha, the image's alpha channel instead (as stored,
// 1 where it has none) in all three.
enum class TextureChannels { Colour, Raw, Alpha };
Image read_texture_image(const std::string& path, TextureChannels channels, int max_side);

// The same of an image file's bytes held in memory (a glTF file's embedded
// image); `format` is the extension its file would have ("png", "jpg").
Image read_texture_image_bytes(const std::string& bytes, const std::string& format, TextureChannels channels,
                               int max_side);

// The inverse of the sRGB transfer function (IEC 61966-2-1): the linear
// value of an encoded one in [0, 1].
float decode_srgb(float encoded);

// The sRGB transfer function (IEC 61966-2-1) of a linear value clamped to
// [0, 1], rounded to the nearest 8-bit code.
std::uint8_t encode_srgb8(float linear);

}  // namespace wp
