// Conforming triangulation of a balanced quadtree and point location in it.
#include "slc/tree/triangulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "finer_neighbour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"

namespace slc {
namespace {

/// Vertices are named by integer coordinates on the grid of half the finest cell edge, so that a
/// corner shared by cells of different sizes is found again whichever cell meets it first.
class VertexTable {
public:
    VertexTable(const Quadtree& tree, Triangulation& mesh)
        : tree_(tree),
          mesh_(mesh),
          shift_(tree.max_depth() + 1),
          step_(tree.edge(0) / static_cast<double>(std::uint64_t{1} << shift_)),
          // About 1.6 vertices per cell (corners shared by four cells, one centre each).
          index_(2 * tree.size()) {}

    /// The vertex at grid point (gx, gy), created on first use.
    std::uint32_t at(std::uint64_t gx, std::uint64_t gy) {
        const std::uint64_t key = (gx << 32) | gy;
        const auto [index, inserted] =
            index_.try_emplace(key, static_cast<std::uint32_t>(mesh_.vertices.size()));
        if (inserted) {
            const Vec2 lo = tree_.root_box().lo;
            mesh_.vertices.push_back(
                {lo.x + static_cast<double>(gx) * step_, lo.y + static_cast<double>(gy) * step_});
        }
        return *index;
    }

private:
    const Quadtree& tree_;
    Triangulation& mesh_;
    int shift_;
    double step_;
    KeyMap<std::uint32_t> index_;
};

/// What triangulate() throws for a quadtree that is not 2:1 balanced (has_finer_neighbour).
constexpr const char* unbalanced = "triangulate: the quadtree is not 2:1 balanced";

}  // namespace

Triangulation triangulate(const Quadtree& tree) {
    Triangulation mesh;
    VertexTable table(tree, mesh);
    fan_leaves(
        tree,
        [&](std::size_t, int, std::uint64_t gx, std::uint64_t gy) { return table.at(gx, gy); },
        [&](std::size_t c, int k, std::uint64_t gx, std::uint64_t gy) {
            // Edges bottom, right, top, left: faces −y, +x, +y, −x.
            constexpr int face[4] = {2, 1, 3, 0};
            return has_finer_neighbour(tree, c, face[k], unbalanced) ? table.at(gx, gy) : no_vertex;
        },
        mesh);
    return mesh;
}

TrianglePoint locate(const Quadtree& tree, const Triangulation& mesh, Vec2 p) {
    p = tree.root_box().clamp(p);
    const std::uint32_t leaf = tree.leaf_at(p);
    // Of the leaf's triangles, the one whose smallest barycentric weight is largest: it contains
    // p, and rounding on a shared edge cannot leave p in none.
    TrianglePoint best;
    double best_min = -std::numeric_limits<double>::infinity();
    for (std::uint32_t t = mesh.cell_offsets[leaf]; t < mesh.cell_offsets[leaf + 1]; ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec2 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
        const double area2 = cross(b - a, c - a);
        const double wa = cross(b - p, c - p) / area2;
        const double wb = cross(c - p, a - p) / area2;
        const double wc = 1.0 - wa - wb;
        const double lowest = std::min({wa, wb, wc});
        if (lowest > best_min) {
            best_min = lowest;
            best = {t, {wa, wb, wc}};
        }
    }
    // Inside the triangle the weights are ≥ 0 but for rounding; clamping keeps every
    // interpolated value a convex combination (the maximum principle of the extensions).
    double sum = 0.0;
    for (double& w : best.weights) sum += (w = std::max(w, 0.0));
    for (double& w : best.weights) w /= sum;
    return best;
}

}  // namespace slc
