#include "import/mesh_invariants.h"

#include <cmath>

#include "core/number_text.h"
#include "import/mesh_file_error.h"

namespace wp {

std::string vector_text(const glm::dvec3& v) {
    return "(" + format_number(v.x) + ", " + format_number(v.y) + ", " + format_number(v.z) + ")";
}

void check_finite_vertex(const glm::dvec3& position) {
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
        throw MeshFileError("vertex " + vector_text(position) + " is not finite");
}

void check_face(std::span<const std::uint32_t> indices, std::size_t vertex_count) {
    if (indices.size() < 3) {
        throw MeshFileError("a face of " + std::to_string(indices.size()) +
                            " vertices (a point or a line) cannot be triangulated");
    }
    for (std::uint32_t index : indices) {
        if (index >= vertex_count) {
            throw MeshFileError("vertex index " + std::to_string(index) + " out of range (" +
                                std::to_string(vertex_count) + " vertices)");
        }
    }
}

}  // namespace wp
