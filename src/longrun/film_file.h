// Film files (.wpfilm): checkpoints and partial films, one format.
//
// Little-endian, in this order (docs/long-renders.md, "Film files"):
//   magic "WPFILM\r\n" (8 bytes), format version (u32), flags (u32; bit 0:
//   sums of squares follow the sums), scene hash (u64), settings hash (u64),
//   estimator (16 bytes, ASCII, zero-padded when shorter), width (u32), height (u32),
//   first work item (u64), end work item (u64), limbs per sum (u32), fraction
//   bits (u32), then the sums (3 per pixel, each WP_FILM_LIMBS u64 limbs,
//   least significant first), the squares if flagged (bit 0), the adaptive
//   round if flagged (bit 1: its pixel count n (u32), its n pixels (u32,
//   ascending) and every pixel's samples before it (u32)), SPPM's photon
//   estimate if flagged (bit 2: photons per iteration (u64), then per pixel
//   the photon counts N, the radii r, from version 4 on the footprints (f64
//   each) and the flux tau (3 f64 per pixel)), and last the FNV-1a 64
//   checksum (u64) of every byte before it.
// The film's range (and round) says everything else: pixel p holds the
// samples s with first <= s * pixels + p < end, so the next work item of a
// checkpoint is its end, and each pixel's sample count follows from the
// range (in a round: from its samples before it and the round's range).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/film.h"
#include "longrun/render_identity.h"

namespace wp {

// Version 2 added the adaptive round (flag bit 1), version 3 SPPM's photon
// estimate (flag bit 2), version 4 the pixels' footprints to it (a radius is
// 0 until the pixel's first visible point sets it); earlier versions are
// read too (a version 3 estimate with footprints 0: unknown).
inline constexpr std::uint32_t kFilmFileVersion = 4;
inline constexpr const char* kFilmFileExtension = ".wpfilm";

// A film file that cannot be used: unreadable, not a film file, truncated,
// corrupted, of a newer version, or made by another render. One line naming
// the file; the CLI exits 3 for it.
class FilmFileError : public std::runtime_error {
 public:
    using std::runtime_error::runtime_error;
};

struct FilmFile {
    RenderIdentity identity;
    Film film;
};

// Writes atomically (throws OutputError).
void write_film_file(const std::string& path, const FilmFile& file);
// Throws FilmFileError.
FilmFile read_film_file(const std::string& path);
// A film file's bytes, read from `path` (named in errors). Throws FilmFileError.
FilmFile parse_film_file(const std::vector<char>& bytes, const std::string& path);

// Throws FilmFileError unless `file` was made by a render of `identity` at
// `width` x `height`: "<path>: made from another scene ..." and the like.
void check_film_matches(const std::string& path, const FilmFile& file, const RenderIdentity& identity, int width,
                        int height);

bool is_film_path(const std::string& path);

}  // namespace wp
