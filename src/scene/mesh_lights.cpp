#include "scene/mesh_lights.h"

namespace wp {

MeshLightTriangles mesh_light_triangles(const Scene& scene) {
    MeshLightTriangles table;
    for (const Light& light : scene.lights) {
        MeshLightTriangles::Range& range = table.ranges.emplace_back();
        if (light.shape != ShapeType::Mesh) continue;
        const Mesh& mesh = scene.meshes[light.index];
        range.first = static_cast<std::uint32_t>(table.triangles.size());
        range.count = static_cast<std::uint32_t>(mesh.triangles.size());
        range.area = mesh_area(mesh);
        std::vector<double> areas;
        for (const glm::uvec3& t : mesh.triangles) {
            table.triangles.push_back({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
            table.materials.push_back(mesh.material);
            areas.push_back(triangle_area(mesh, t));
        }
        const std::vector<double> cdf = cumulative_distribution(areas);
        table.cdf.insert(table.cdf.end(), cdf.begin(), cdf.end());
    }
    return table;
}

}  // namespace wp
