// Bit-for-bit comparison of film sums (kernels/shared/film_sum.h), as the
// tests that require a render's exact bits compare them.
#pragma once

#include <cstring>
#include <vector>

#include "core/film.h"

namespace wp::test {

inline bool same_sums(const std::vector<film_sum>& a, const std::vector<film_sum>& b) {
    // memcmp must not see an empty vector's null data, even for zero bytes (UBSan)
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), sizeof(film_sum) * a.size()) == 0);
}

}  // namespace wp::test
