// The triangles next-event estimation samples on emitting meshes, shared by
// the reference and the kernels' upload so that both choose alike: for each
// mesh light, its triangles in file order with the cumulative fraction of the
// mesh's area (the last 1), computed in double. A triangle is chosen in
// proportion to its area, then a point uniformly on it: the point's density
// is 1 / (the mesh's area) wherever it lands.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "scene/scene.h"

namespace wp {

struct MeshLightTriangles {
    struct Range {
        std::uint32_t first = 0, count = 0;  // in `triangles`; count 0 for lights that are not meshes
        double area = 0.0;                   // the mesh's
    };
    std::vector<Range> ranges;  // one per Scene::lights entry
    std::vector<std::array<glm::dvec3, 3>> triangles;
    std::vector<int> materials;  // per triangle
    std::vector<double> cdf;     // per triangle, cumulative within its mesh
};

MeshLightTriangles mesh_light_triangles(const Scene& scene);

}  // namespace wp
