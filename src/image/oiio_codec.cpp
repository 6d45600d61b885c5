// The module libwavepath_oiio.so: image_codec.h's calls, made with OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>
#include <optional>

#include "image/image_codec.h"

namespace {

std::string error_or_unknown(const std::string& error) {
    return error.empty() ? std::string("unknown OpenImageIO error") : error;
}

std::string write(const std::string& file, int width, int height, bool srgb8, const void* rgb,
                  const char* compression) {
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(file);
    if (!output) return error_or_unknown(OIIO::geterror());
    const OIIO::TypeDesc type = srgb8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(width, height, 3, type);
    spec.attribute("oiio:ColorSpace", srgb8 ? "sRGB" : "Linear");
    if (compression) spec.attribute("compression", compression);
    if (!output->open(file, spec) || !output->write_image(type, rgb) || !output->close())
        return error_or_unknown(output->geterror());
    return {};
}

std::string read(const std::string& file, const std::string* bytes, wp::image_codec::ReadChannels wanted, int max_side,
                 wp::image_codec::Pixels& pixels) {
    // Colours as stored, not multiplied by their alpha (OpenImageIO's default for PNG), as
    // Mitsuba's bitmap reads them: the alpha of a texture is not part of its colour.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // Bytes in memory through a proxy, which OpenImageIO 2.4 takes from the configuration where
    // there is one (its `ioproxy` argument alone is then ignored).
    std::optional<OIIO::Filesystem::IOMemReader> memory;
    void* proxy = nullptr;
    if (bytes) {
        proxy = &memory.emplace(bytes->data(), bytes->size());
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    }
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(file, &config, memory ? &*memory : nullptr);
    if (!input) return error_or_unknown(OIIO::geterror());
    const OIIO::ImageSpec& spec = input->spec();
    pixels.width = spec.width;
    pixels.height = spec.height;
    pixels.channels = spec.nchannels;
    pixels.floating_point = spec.format.is_floating_point();
    if (spec.width > max_side || spec.height > max_side) return {};
    const std::size_t texels = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
    int begin = 0, end = std::min(spec.nchannels, 3);
    if (wanted == wp::image_codec::ReadChannels::Alpha) {
        if (spec.alpha_channel < 0) {
            pixels.values.assign(texels, 1.0f);
            return {};
        }
        begin = spec.alpha_channel;
        end = begin + 1;
    }
    pixels.values.resize(texels * static_cast<std::size_t>(end - begin));
    if (!input->read_image(0, 0, begin, end, OIIO::TypeDesc::FLOAT, pixels.values.data()))
        return error_or_unknown(input->geterror());
    return {};
}

constexpr wp::image_codec::Codec kCodec{write, read};

}  // namespace

extern "C" const wp::image_codec::Codec* wavepath_image_codec() { return &kCodec; }
