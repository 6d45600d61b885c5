// Sane limits on what a scene (and the command line's overrides) may ask
// for; docs/scene-format.md lists them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace wp {

inline constexpr int kMaxResolution = 16384;
inline constexpr std::int64_t kMaxPixels = std::int64_t{1} << 27;
inline constexpr int kMaxSpp = 1 << 20;
inline constexpr int kMaxDepthLimit = 100000;
// Photons per SPPM iteration (a photon's index is 32 bits; the wavefront
// emits an iteration's photons as one pass).
inline constexpr std::int64_t kMaxPhotons = std::int64_t{1} << 30;
// What a hit's shape index holds (kernels/interface/scene_layout.h, WP_SHAPE_INDEX_MASK + 1).
inline constexpr std::size_t kMaxTriangles = std::size_t{1} << 29;

// The widest pixel filter, in pixels: a tent's radius, a gaussian's window
// (4 standard deviations).
inline constexpr double kMaxFilterRadius = 16.0;
// A bitmap texture's side, and the texels of all a scene's textures
// together (float RGB: 768 MiB of device memory; texel indices stay far
// inside 32 bits).
inline constexpr int kMaxTextureSide = 16384;
inline constexpr std::size_t kMaxTextureTexels = std::size_t{1} << 26;

// The smallest microfacet roughness alpha: D's peak 1 / (pi alpha^2) then
// stays far inside float's range (3.2e7), and the lobe is narrower than
// anything a pixel resolves.
inline constexpr double kMinRoughness = 1e-4;

}  // namespace wp
