// The meshes of Mitsuba's shapes that wavepath has no primitive for, in
// their own coordinates, and the vertex normals Mitsuba computes for meshes
// that have none (docs/scene-format.md, "Mitsuba XML").
#pragma once

#include "import/imported_scene.h"
#include "scene/scene.h"

namespace wp {

// Segments of a disk's rim: its triangle fan's area is
// (n / (2 pi)) sin(2 pi / n) = 1 - 2.5e-5 of the disk's.
inline constexpr int kDiskSegments = 512;

// Mitsuba's `cube`: [-1, 1]^3, 12 triangles, counter-clockwise seen from
// outside (no vertex normals: its faces are flat), with Mitsuba's uvs: each
// face's own four corners, the unit uv square over it.
ImportedMesh cube_mesh();

// Mitsuba's `disk`: the unit disk in the xy plane facing +z, as a fan of
// kDiskSegments triangles around its centre (corners computed in float, so
// that a PLY file of them holds them exactly).
ImportedMesh disk_mesh();

// The meshes of an imported file, with its node transforms, as one mesh in
// the file's coordinates. `exact` says whether every node transform was the
// identity (the positions are then the file's own floats).
ImportedMesh merge_imported(const ImportedScene& scene, bool& exact);

// Mitsuba's vertex normals for a mesh without them (Mesh::recompute_vertex_normals,
// after Thuermer and Wuethrich 1998): each triangle's unit normal, weighted by
// its angle at the vertex, summed and normalized; in world space, in double.
// A vertex that no triangle touches gets its neighbour-free default (0, 0, 1).
void compute_vertex_normals(Mesh& mesh);

}  // namespace wp
