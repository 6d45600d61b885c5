// What wavepath requires of every mesh a file holds, whoever read it:
// wavepath-import checks assimp's meshes before its post-processing (which
// reads vertices through the indices and sorts positions, where a NaN
// merges unrelated vertices), and wavepath checks the meshes it gets back.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <string>

namespace wp {

// "(x, y, z)" for messages.
std::string vector_text(const glm::dvec3& v);

// Throws MeshFileError unless every coordinate is finite.
void check_finite_vertex(const glm::dvec3& position);

// Throws MeshFileError unless the face has at least 3 vertices (a point or a
// line cannot be triangulated) and each index is below `vertex_count`.
void check_face(std::span<const std::uint32_t> indices, std::size_t vertex_count);

}  // namespace wp
