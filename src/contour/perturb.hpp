#pragma once
// Perturbation (§2.1) of the contouring mesh's vertices where |G| ≤ η, for both dimensions: the
// mesh's simplices differ, the rule does not.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/point_text.hpp"
#include "slc/core/space.hpp"

namespace slc::contouring {

/// The first displacement is this fraction of the finest cell edge h, doubled at each attempt up
/// to the sixth, 3.2% of h: well below the smallest altitude of the mesh's simplices (35% of h
/// for the triangles of the plane, an eighth of h for the tetrahedra of space), so the mesh stays
/// valid. The attempts after it keep that length in new directions: a vertex on a flat part of
/// the zero set with η a fair part of h (η = ε/100 of a coarse ε) needs a direction well off the
/// plane, which six directions need not give.
inline constexpr double first_perturbation = 1e-3;
inline constexpr int doubled_perturbations = 6;
inline constexpr int max_perturbations = 12;

/// Moves the vertices whose values are within η of zero off it, all of one attempt in one batch
/// `g(points, values)`: at attempt k, vertex v goes to where it was plus first_perturbation·2^k·h
/// times the unit vector `direction(v, k)`. Throws NumericalFailure, naming the place, when one
/// is still within η after max_perturbations attempts. Returns the number of vertices moved.
template <int dim, class Evaluate, class Direction>
std::size_t perturb_vertices(std::vector<PointOf<dim>>& vertices, std::vector<double>& values,
                             const Evaluate& g, double eta, double h, const Direction& direction) {
    using Point = PointOf<dim>;
    struct Pending {
        std::size_t vertex;
        Point original;
    };
    std::vector<Pending> todo;
    for (std::size_t v = 0; v < vertices.size(); ++v)
        if (std::abs(values[v]) <= eta) todo.push_back({v, vertices[v]});
    const std::size_t moved = todo.size();
    for (int k = 0; !todo.empty(); ++k) {
        if (k == max_perturbations) {
            throw NumericalFailure(fmt::format(
                "G vanishes (|G| <= eta = {}) at and around {} after {} perturbations up to "
                "{:.3g}: G and its gradient seem to vanish together, so the contour is "
                "ill-posed there",
                eta, point_text(todo.front().original, 6), max_perturbations,
                first_perturbation * std::ldexp(h, doubled_perturbations - 1)));
        }
        const double step =
            first_perturbation * std::ldexp(h, std::min(k, doubled_perturbations - 1));
        std::vector<Point> points;
        points.reserve(todo.size());
        for (const Pending& p : todo) points.push_back(p.original + step * direction(p.vertex, k));
        std::vector<double> got(points.size());
        g(points, got);
        std::vector<Pending> left;
        for (std::size_t i = 0; i < todo.size(); ++i) {
            vertices[todo[i].vertex] = points[i];
            values[todo[i].vertex] = got[i];
            if (std::abs(got[i]) <= eta) left.push_back(todo[i]);
        }
        todo = std::move(left);
    }
    return moved;
}

}  // namespace slc::contouring
