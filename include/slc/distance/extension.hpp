/// @file
/// Extension of values given at the vertices of Γ (velocities, usually) to the whole plane
/// (paper §1.3): the nearest-point extension W(x) = u(y*(x)), linear in u along the nearest
/// segment, and the numerical Whitney extension, the continuous piecewise-linear interpolant of the
/// nearest-point extension on the triangulated distance tree. Both obey the maximum principle:
/// every extended value is a convex combination of vertex values, so no component exceeds its
/// largest value on Γ.
#pragma once

#include <span>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/distance_tree.hpp"

namespace slc {

/// The nearest-point extension at a point whose closest point is p (signed or not: the sign is
/// not used): the vertex values of p's segment interpolated linearly at p. T is double or Vec2.
/// O(1).
template <class T>
T nearest_point_extension(const Interface& curves, std::span<const T> values,
                          const ClosestPoint& p) {
    const T& a = values[p.segment];
    const T& b = values[curves.next(p.segment)];
    return (1.0 - p.t) * a + p.t * b;
}

/// The nearest-point extension at arbitrary points: one closest-point query each, in parallel.
template <class T>
std::vector<T> nearest_point_extension(const DistanceTree& tree, std::span<const T> values,
                                       std::span<const Vec2> xs) {
    if (values.size() != tree.curves().size()) {
        throw InvalidInput("nearest-point extension: need one value per interface vertex");
    }
    std::vector<T> out(xs.size());
    parallel_for(xs.size(), [&](std::size_t i) {
        out[i] = nearest_point_extension(tree.curves(), values, tree.nearest_point(xs[i]));
    });
    return out;
}

/// The numerical Whitney extension of vertex values, built on a triangulated distance tree:
/// continuous everywhere, linear on each triangle, equal to the nearest-point extension at the
/// triangulation's vertices. Points outside the domain take the value at the nearest domain point.
template <class T>
class WhitneyExtension {
public:
    /// Precondition: tree was built with Options::triangulate. values: one per interface vertex.
    /// Cost O(triangulation vertices), using their stored nearest points.
    WhitneyExtension(const DistanceTree& tree, std::span<const T> values) : tree_(&tree) {
        if (values.size() != tree.curves().size()) {
            throw InvalidInput("Whitney extension: need one value per interface vertex");
        }
        if (tree.triangulation().triangles.empty()) {
            throw InvalidInput(
                "Whitney extension: the distance tree was built without triangulation");
        }
        const auto nearest = tree.vertex_closest_points();
        vertex_values_.resize(nearest.size());
        parallel_for(nearest.size(), [&](std::size_t v) {
            vertex_values_[v] = nearest_point_extension(tree.curves(), values, nearest[v]);
        });
    }

    /// The extended value at x. O(log N).
    T operator()(Vec2 x) const {
        const Triangulation& mesh = tree_->triangulation();
        const TrianglePoint p = locate(tree_->tree(), mesh, x);
        const auto& tri = mesh.triangles[p.triangle];
        return p.weights[0] * vertex_values_[tri[0]] + p.weights[1] * vertex_values_[tri[1]] +
               p.weights[2] * vertex_values_[tri[2]];
    }

    /// The extended values at a batch of points, in parallel.
    std::vector<T> operator()(std::span<const Vec2> xs) const {
        std::vector<T> out(xs.size());
        parallel_for(xs.size(), [&](std::size_t i) { out[i] = (*this)(xs[i]); });
        return out;
    }

    /// Values at the triangulation's vertices.
    std::span<const T> vertex_values() const { return vertex_values_; }

private:
    const DistanceTree* tree_;
    std::vector<T> vertex_values_;
};

}  // namespace slc
