/// @file
/// The snapping Box::square and Box3::cube share: a square (cube) about a centre, exactly as wide
/// along every axis, which c ± b need not be, as each coordinate rounds differently.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

namespace slc::detail {

/// The low corner and the width of a square (n = 2) or cube (n = 3) that holds [c − b, c + b]ⁿ
/// and is exactly as wide along every axis: its corners snapped outward to a grid of about 2^−24
/// of its width. For b > 0 and c finite.
template <std::size_t n>
std::pair<std::array<double, n>, double> exact_cube(const std::array<double, n>& c, double b) {
    int e = 0;
    (void)std::frexp(2.0 * b, &e);
    const double q = std::ldexp(1.0, e - 24);  // 2b < 2^e: under 2^24 grid steps
    // Multiples of q below 2^53 q add and subtract exactly: lo + w − lo is w.
    const double w = std::ceil((2.0 * b + q) / q) * q;
    std::array<double, n> lo{};
    for (std::size_t i = 0; i < n; ++i) lo[i] = std::floor((c[i] - b) / q) * q;
    return {lo, w};
}

}  // namespace slc::detail
