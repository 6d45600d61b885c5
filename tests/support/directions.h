// Deterministic unit directions spread evenly over the sphere, for tests
// that sweep normals or incident directions.
#pragma once

#include <cmath>
#include <glm/vec3.hpp>

namespace wp::test {

// Point i of a Fibonacci lattice of `count` points on the unit sphere.
inline glm::dvec3 spread_direction(int i, int count) {
    double z = 1.0 - (2.0 * i + 1.0) / count;
    double r = std::sqrt(1.0 - z * z);
    double phi = 2.39996322972865332 * i;  // the golden angle
    return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace wp::test
