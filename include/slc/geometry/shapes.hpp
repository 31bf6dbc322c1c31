/// @file
/// Built-in shapes: polygons sampling simple closed curves, counterclockwise, for problems,
/// tests, benchmarks and the demo.
#pragma once

#include <functional>
#include <vector>

#include "slc/core/vec2.hpp"

/// Built-in shapes: counterclockwise polygons sampling simple closed curves.
namespace slc::shapes {

/// n vertices on the circle of radius r about centre, counterclockwise from angle phase.
std::vector<Vec2> circle(Vec2 centre, double r, int n, double phase = 0.0);

/// n vertices of the star-shaped curve r(θ) about centre, θ = phase + 2πk/n, counterclockwise.
/// Precondition: r(θ) > 0.
std::vector<Vec2> polar(Vec2 centre, const std::function<double(double)>& r, int n,
                        double phase = 0.0);

/// The three-bladed propeller r(θ) = r0 (1 + a cos 3θ) used for the paper's Figures 3 and 6,
/// with r0 = 0.5, a = 0.5 by default: blades reaching 0.75 from the centre, waists at 0.25.
std::vector<Vec2> propeller(int n, Vec2 centre = {}, double r0 = 0.5, double a = 0.5,
                            double phase = 0.0);

/// The axis-aligned rectangle [lo, hi], counterclockwise from lo, each side split into
/// per_side segments.
std::vector<Vec2> rectangle(Vec2 lo, Vec2 hi, int per_side = 1);

}  // namespace slc::shapes
