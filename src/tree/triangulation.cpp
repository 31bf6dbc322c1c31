// Conforming triangulation of a balanced quadtree and point location in it.
#include "slc/tree/triangulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

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
    /// Grid units per cell edge at a level.
    std::uint64_t units(int level) const { return std::uint64_t{1} << (shift_ - level); }

private:
    const Quadtree& tree_;
    Triangulation& mesh_;
    int shift_;
    double step_;
    KeyMap<std::uint32_t> index_;
};

/// True when the neighbour of leaf c across the edge in direction (dx, dy) is finer than c.
/// Throws when it is a leaf coarser than c's parent: the tree is not 2:1 balanced (checked here,
/// where every leaf's four neighbours are found anyway, instead of in a pass of its own).
bool has_finer_neighbour(const Quadtree& tree, std::size_t c, int dx, int dy) {
    const std::uint32_t n = tree.neighbour(c, dx, dy);
    if (n == Quadtree::no_cell) return false;
    const int level = tree.cell(c).level;
    if (tree.cell(n).level < level - 1)
        throw InvalidInput("triangulate: the quadtree is not 2:1 balanced");
    return tree.cell(n).level == level && !tree.is_leaf(n);
}

void fan_leaf(const Quadtree& tree, std::size_t c, VertexTable& table, Triangulation& mesh) {
    const auto& cell = tree.cell(c);
    const std::uint64_t u = table.units(cell.level);
    const std::uint64_t x0 = cell.ix * u, y0 = cell.iy * u, h = u / 2;
    // Boundary counterclockwise from the low-left corner: bottom, right, top, left edges, each
    // with its midpoint when the neighbour across it is finer.
    const bool finer[4] = {has_finer_neighbour(tree, c, 0, -1), has_finer_neighbour(tree, c, 1, 0),
                           has_finer_neighbour(tree, c, 0, 1), has_finer_neighbour(tree, c, -1, 0)};
    const std::uint32_t centre = table.at(x0 + h, y0 + h);
    std::array<std::uint32_t, 8> ring{};
    std::size_t n = 0;
    ring[n++] = table.at(x0, y0);
    if (finer[0]) ring[n++] = table.at(x0 + h, y0);
    ring[n++] = table.at(x0 + u, y0);
    if (finer[1]) ring[n++] = table.at(x0 + u, y0 + h);
    ring[n++] = table.at(x0 + u, y0 + u);
    if (finer[2]) ring[n++] = table.at(x0 + h, y0 + u);
    ring[n++] = table.at(x0, y0 + u);
    if (finer[3]) ring[n++] = table.at(x0, y0 + h);
    for (std::size_t k = 0; k < n; ++k)
        mesh.triangles.push_back({centre, ring[k], ring[(k + 1) % n]});
}

}  // namespace

Triangulation triangulate(const Quadtree& tree) {
    Triangulation mesh;
    VertexTable table(tree, mesh);
    mesh.cell_offsets.reserve(tree.size() + 1);
    mesh.triangles.reserve(4 * tree.size());  // 4 to 8 per leaf, about 3 leaves in 4 cells
    mesh.cell_offsets.push_back(0);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        if (tree.is_leaf(c)) fan_leaf(tree, c, table, mesh);
        mesh.cell_offsets.push_back(static_cast<std::uint32_t>(mesh.triangles.size()));
    }
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
