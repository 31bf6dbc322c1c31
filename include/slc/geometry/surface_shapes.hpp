/// @file
/// Built-in closed surfaces (DESIGN §8): spheres, tori, boxes and the Enright test's sphere,
/// each valid and oriented outward; and the union of disjoint surfaces. The 3D counterpart of
/// shapes.hpp.
#pragma once

#include <vector>

#include "slc/core/vec3.hpp"
#include "slc/geometry/surface.hpp"

namespace slc {

/// An icosphere: the icosahedron inscribed in the sphere, each triangle split into four
/// `subdivisions` times with new vertices pushed out to the sphere: 20·4^subdivisions triangles,
/// genus 0. Throws InvalidInput unless radius > 0 and 0 <= subdivisions <= 10.
Surface sphere(Vec3 center, double radius, int subdivisions);

/// A torus around the z-axis through center: tube of radius minor around the circle of radius
/// major; `around` quads along the big circle and `across` around the tube, each split in two:
/// 2·around·across triangles, genus 1. Throws InvalidInput unless 0 < minor < major and
/// around, across >= 3.
Surface torus(Vec3 center, double major, double minor, int around, int across);

/// The box [lo, hi] with each face an n × n grid of squares split in two: 12·n² triangles, sharp
/// edges and corners. Throws InvalidInput unless lo < hi componentwise and 1 <= n <= 1000.
Surface box_surface(Vec3 lo, Vec3 hi, int n);

/// The sphere of Enright et al.'s deformation test (J. Comput. Phys. 183, 2002): radius 0.15,
/// centre (0.35, 0.35, 0.35), as an icosphere.
Surface enright_sphere(int subdivisions);

/// The surfaces one after another (vertex indices shifted): their union when they are disjoint.
Surface join(const std::vector<Surface>& parts);

}  // namespace slc
