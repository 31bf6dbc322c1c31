/// @file
/// Named tolerances shared by the modules, each with the reason for its size.
#pragma once

#include <limits>

/// Named tolerances shared by the modules.
namespace slc::tolerance {

/// Relative size, against the domain width, below which two consecutive input points are the same
/// point and one is dropped: far above rounding (1e-16), far below any useful segment.
inline constexpr double duplicate_point = 1e-12;

/// Largest magnitude of a coordinate, of an input point or of a domain corner. Squared distances
/// across a domain of this size (about 1e201) stay far from the overflow of doubles (1.8e308).
inline constexpr double max_coordinate = 1e100;

/// Smallest width of a domain: squared distances of its cells (about 1e-200 and below) stay far
/// from the underflow of doubles (2.2e-308).
inline constexpr double min_domain_width = 1e-100;

/// Smallest edge of a tree cell, relative to the largest coordinate magnitude of the domain: 2^-42
/// is about 1000 spacings of doubles there, so that a cell still holds distinct points.
inline constexpr double min_relative_cell = 0x1p-42;

/// The smallest |G| that doubles tell from zero in a domain (a Box or a Box3): two ulps of its
/// largest coordinate, the rounding of a distance evaluated there. No contour's root or midpoint
/// can be brought closer to the zero set, so η and ε are never below it (contour(),
/// contour_surface()).
template <class Domain>
double rounding_floor(const Domain& domain) {
    return 2.0 * std::numeric_limits<double>::epsilon() * domain.largest_magnitude();
}

}  // namespace slc::tolerance
