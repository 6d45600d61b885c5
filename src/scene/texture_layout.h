// The scene's textures as the shared code reads them (kernels/shared/texture.h),
// for one precision: the device upload takes SharedMath<float>'s, the
// reference its own Real's.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/shared_math.h"
#include "scene/scene.h"

namespace wp {

template <class Real>
struct TextureLayout {
    // One per texture, and never empty: every lane of a kernel evaluates
    // texture 0 where its material has none (a zero checkerboard then).
    std::vector<typename SharedMath<Real>::TextureDescriptor> descriptors;
    // The bitmaps' texels, 3 values each, and never empty: a checkerboard's
    // descriptor says 1 x 1 texels at 0, so that the bitmap path every lane
    // also evaluates reads inside the buffer. One spare value ends it, which
    // gather_rgb's 4-wide loads read (shared/prelude.h).
    std::vector<Real> texels;
    // Per material and TexturedParameter: its texture, or WP_NO_TEXTURE.
    std::vector<std::array<std::uint32_t, kTexturedParameters>> material_textures;
};

inline std::uint32_t texture_filter(TextureFilter filter) {
    return filter == TextureFilter::Nearest ? WP_FILTER_NEAREST : WP_FILTER_BILINEAR;
}

inline std::uint32_t texture_wrap(TextureWrap wrap) {
    return wrap == TextureWrap::Mirror ? WP_WRAP_MIRROR : (wrap == TextureWrap::Clamp ? WP_WRAP_CLAMP : WP_WRAP_REPEAT);
}

template <class Real>
TextureLayout<Real> texture_layout(const Scene& scene) {
    TextureLayout<Real> layout;
    for (const Texture& texture : scene.textures) {
        typename SharedMath<Real>::TextureDescriptor d{};
        const bool bitmap = texture.type == TextureType::Bitmap;
        d.type = bitmap ? WP_TEXTURE_BITMAP : WP_TEXTURE_CHECKERBOARD;
        d.filter = texture_filter(texture.filter);
        d.wrap = texture_wrap(texture.wrap);
        d.width = bitmap ? static_cast<std::uint32_t>(texture.width) : 1u;
        d.height = bitmap ? static_cast<std::uint32_t>(texture.height) : 1u;
        d.first_texel = bitmap ? static_cast<std::uint32_t>(layout.texels.size() / 3) : 0u;
        for (int i = 0; i < 6; ++i) d.to_uv[i] = static_cast<Real>(texture.to_uv[i]);
        for (int i = 0; i < 3; ++i) {
            d.color0[i] = static_cast<Real>(texture.color0[i]);
            d.color1[i] = static_cast<Real>(texture.color1[i]);
        }
        if (bitmap) layout.texels.insert(layout.texels.end(), texture.texels.begin(), texture.texels.end());
        layout.descriptors.push_back(d);
    }
    if (layout.descriptors.empty()) {
        typename SharedMath<Real>::TextureDescriptor black{};
        black.type = WP_TEXTURE_CHECKERBOARD;
        black.width = black.height = 1u;
        layout.descriptors.push_back(black);
    }
    if (layout.texels.empty()) layout.texels.resize(3, Real(0));
    layout.texels.push_back(Real(0));
    for (const Material& m : scene.materials) {
        std::array<std::uint32_t, kTexturedParameters> slots{};
        for (std::size_t p = 0; p < kTexturedParameters; ++p)
            slots[p] = m.textures[p] == kNoTexture ? WP_NO_TEXTURE : static_cast<std::uint32_t>(m.textures[p]);
        layout.material_textures.push_back(slots);
    }
    return layout;
}

}  // namespace wp
