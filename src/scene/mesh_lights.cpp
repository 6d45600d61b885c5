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
        double running = 0.0;
        for (const glm::uvec3& t : mesh.triangles) {
            table.triangles.push_back({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
            table.materials.push_back(mesh.material);
            running += triangle_area(mesh, t);
            table.cdf.push_back(running / range.area);
        }
        table.cdf.back() = 1.0;
    }
    return table;
}

}  // namespace wp
