#include "scene/conductors.h"

#include <array>
#include <string_view>

namespace wp {
namespace {

struct NamedConductor {
    std::string_view name;
    ComplexIndex index;
};

// "none": eta 0, k 1, whose Fresnel reflectance is 1 at every angle (the
// index i: |r_s| = |r_p| = 1), Mitsuba's perfect mirror.
constexpr std::array kConductors{
    NamedConductor{"none", {glm::dvec3(0.0), glm::dvec3(1.0)}},
};

}  // namespace

std::optional<ComplexIndex> named_conductor(const std::string& name) {
    for (const NamedConductor& c : kConductors)
        if (c.name == name) return c.index;
    return std::nullopt;
}

std::string named_conductors() {
    std::string names;
    for (const NamedConductor& c : kConductors) names += (names.empty() ? "" : ", ") + std::string(c.name);
    return names;
}

}  // namespace wp
