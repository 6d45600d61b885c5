#include "scene/named_media.h"

#include <algorithm>
#include <cctype>

#include "scene/named_media_table.h"

namespace wp {

using named_media_detail::kConductors;
using named_media_detail::kDielectrics;

std::optional<ComplexIor> named_conductor(std::string_view name) {
    for (const auto& row : kConductors) {
        if (name == row.name) {
            return ComplexIor{{row.eta[0], row.eta[1], row.eta[2]}, {row.k[0], row.k[1], row.k[2]}};
        }
    }
    return std::nullopt;
}

std::optional<double> named_ior(std::string_view name) {
    std::string lower(name);
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const auto& row : kDielectrics) {
        if (lower == row.name) return row.ior;
    }
    return std::nullopt;
}

namespace {
template <class Rows>
std::string names_of(const Rows& rows) {
    std::string list;
    for (const auto& row : rows) list += (list.empty() ? "" : ", ") + std::string(row.name);
    return list;
}
}  // namespace

std::string named_conductor_list() { return names_of(kConductors); }
std::string named_ior_list() { return names_of(kDielectrics); }

}  // namespace wp
