// Where the precision tests of shared/offset.h and shared/hit_point.h put a
// shape: at scales from 1e-6 to 1e6, and placed (each test lists its
// Placements) near the origin, far from it, or hit from far away; distances
// measured in long double.
#pragma once

#include <glm/glm.hpp>

namespace wp::test {

using LongVec = glm::vec<3, long double>;

template <class Vector>
LongVec to_long(const Vector& v) {
    return LongVec(v);
}

inline constexpr double kShapeScales[] = {1e-6, 1e-3, 1.0, 1e3, 1e6};

// Where the shape sits and where rays come from, in units of the shape's size.
struct Placement {
    const char* name;
    glm::dvec3 shape_position;  // added to the shape's coordinates
    glm::dvec3 ray_origin;      // where rays start, or the centre of where they start
};

}  // namespace wp::test
