// Mitsuba's `serialized` mesh files (docs/scene-format.md, "Mitsuba XML"),
// read as Mitsuba's documentation ("Serialized mesh format") and its reader
// (src/shapes/serialized.cpp) describe them: little-endian; per mesh a
// header (uint16 0x041C, uint16 version 3 or 4) and a zlib stream of flags
// (uint32), the name (version 4, NUL-terminated), vertex and triangle counts
// (uint64), positions, then normals, texture coordinates and colours where
// the flags say so, in float or double, then uint32 triangle indices; and at
// the end of the file the offset of every mesh (uint64; uint32 in version 3)
// and their count (uint32).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "import/imported_scene.h"

namespace wp {

// The mesh `shape_index` of the file's bytes, in the file's coordinates
// (positions and, where the file has them, normals; texture coordinates and
// colours are skipped). Throws MeshFileError for anything malformed: a
// wrong signature or version, an index beyond the table, offsets outside
// the file, a zlib stream that is corrupt or ends early, counts beyond what
// the stream can hold, non-finite values and indices out of range.
ImportedMesh parse_serialized_mesh(std::string_view bytes, std::int64_t shape_index);

// The same, from a file (MeshFileError when it cannot be read).
ImportedMesh read_serialized_mesh(const std::filesystem::path& path, std::int64_t shape_index);

}  // namespace wp
