// The calls into OpenImageIO, which live in a module of their own
// (libwavepath_oiio.so) that image_io.cpp opens the first time an image is
// read or written. Linked into the binaries, OpenImageIO brings 260 shared
// libraries, and the dynamic loader spent 0.2 CPU s relocating them at the
// start of every process, also of those that read no image: every scene
// error, every CLI call (docs/bad-input.md, "Starting a process").
//
// The module throws nothing across this boundary: each call returns the
// error OpenImageIO gave, or an empty string on success.
#pragma once

#include <string>
#include <vector>

namespace wp::image_codec {

// An image file's header and, unless it is larger than asked for, the
// channels asked for (ReadChannels) as floats, row 0 the file's top row.
struct Pixels {
    int width = 0;
    int height = 0;
    int channels = 0;             // as stored
    bool floating_point = false;  // samples stored as floats (EXR, HDR, PFM), not integers
    std::vector<float> values;    // empty when width or height is over the read's max_side
};

// Which channels a read gives: the first min(channels, 3), or the alpha channel alone (1 where the
// image has none).
enum class ReadChannels { Colour, Alpha };

struct Codec {
    // Writes `width` x `height` RGB pixels to `file`, whose extension picks
    // the writer: 8-bit sRGB-encoded samples if `srgb8`, else floats.
    // `compression` is OpenImageIO's attribute, or nullptr for its default.
    std::string (*write)(const std::string& file, int width, int height, bool srgb8, const void* rgb,
                         const char* compression);
    // Reads `file` into `pixels` (see Pixels: no values if a side is over `max_side`); or, where
    // `bytes` is not null, the image file they hold, whose format `file`'s extension names.
    std::string (*read)(const std::string& file, const std::string* bytes, ReadChannels channels, int max_side,
                        Pixels& pixels);
};

}  // namespace wp::image_codec

// The module's one entry point, found by name.
extern "C" const wp::image_codec::Codec* wavepath_image_codec();
