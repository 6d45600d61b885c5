// The conductors a scene may name (`material` of conductor and
// roughconductor, docs/scene-format.md): Mitsuba 3's names, with the complex
// index of refraction eta + i k per RGB channel that its RGB variants use.
#pragma once

#include <glm/vec3.hpp>
#include <optional>
#include <string>

namespace wp {

struct ComplexIndex {
    glm::dvec3 eta, k;
};

// The index of the conductor called `name`, or nothing for an unknown name.
std::optional<ComplexIndex> named_conductor(const std::string& name);

// The known names, comma-separated, for messages.
std::string named_conductors();

}  // namespace wp
