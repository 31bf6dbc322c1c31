/// @file
/// Named tolerances shared by the modules, each with the reason for its size.
#pragma once

/// Named tolerances shared by the modules.
namespace slc::tolerance {

/// Relative size, against the domain width, below which two consecutive input points are the same
/// point and one is dropped: far above rounding (1e-16), far below any useful segment.
inline constexpr double duplicate_point = 1e-12;

}  // namespace slc::tolerance
