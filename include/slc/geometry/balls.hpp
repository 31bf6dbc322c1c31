/// @file
/// The exact signed distance to the boundary of a union of discs (dim = 2) or balls (dim = 3):
/// the exact solution of discs or balls growing at unit normal speed (paper Eq. 11 for Table 6
/// and its surface counterpart), right in the cusps and islands where they merge.
#pragma once

#include <span>

#include "slc/core/space.hpp"

namespace slc {

/// A disc (dim = 2) or a ball (dim = 3).
template <int dim>
struct Ball {
    PointOf<dim> centre;
    double radius = 0.0;
};

/// The signed distance from x to the boundary of the union of the balls, negative inside.
/// The nearest boundary point lies inside a face (the radial projection onto a sphere), inside an
/// edge (the nearest point of the circle where two spheres meet, dim = 3) or at a corner (where
/// two circles meet in the plane, three spheres in space): each candidate that no other ball
/// covers is a boundary point, and the nearest of them is the nearest boundary point. O(n^dim)
/// for n balls. An empty list gives +infinity. Balls of radius ≤ 0 are left out.
template <int dim>
double union_of_balls_distance(std::span<const Ball<dim>> balls, PointOf<dim> x);

}  // namespace slc
