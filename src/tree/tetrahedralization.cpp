// Conforming tetrahedral mesh of a balanced octree: cones from leaf centres over fans of faces.
#include "slc/tree/tetrahedralization.hpp"

#include <fmt/format.h>

#include <utility>

#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"

namespace slc {
namespace {

using GridPoint = std::array<std::uint64_t, 3>;

/// The mesh's vertices by grid point, created on first use, and the set of leaf corners.
class VertexTable {
public:
    VertexTable(const Octree& tree, Tetrahedralization& mesh)
        : tree_(tree),
          mesh_(mesh),
          step_(tree.edge(0) / static_cast<double>(std::uint64_t{1} << (tree.max_depth() + 1))),
          index_(4 * tree.size()),
          corners_(2 * tree.size()) {}

    /// The vertex at grid point p.
    std::uint32_t at(const GridPoint& p) {
        const auto [index, inserted] =
            index_.try_emplace(Tetrahedralization::key(p[0], p[1], p[2]),
                               static_cast<std::uint32_t>(mesh_.vertices.size()));
        if (inserted) {
            const Vec3 lo = tree_.root_box().lo;
            mesh_.vertices.push_back({lo.x + static_cast<double>(p[0]) * step_,
                                      lo.y + static_cast<double>(p[1]) * step_,
                                      lo.z + static_cast<double>(p[2]) * step_});
            mesh_.grid.push_back({static_cast<std::uint32_t>(p[0]),
                                  static_cast<std::uint32_t>(p[1]),
                                  static_cast<std::uint32_t>(p[2])});
        }
        return *index;
    }

    /// Records p as a corner of a leaf.
    void add_corner(const GridPoint& p) {
        corners_.try_emplace(Tetrahedralization::key(p[0], p[1], p[2]), 1);
    }
    /// True when p is a corner of some leaf.
    bool is_corner(const GridPoint& p) const {
        return corners_.contains(Tetrahedralization::key(p[0], p[1], p[2]));
    }

private:
    const Octree& tree_;
    Tetrahedralization& mesh_;
    double step_;
    KeyMap<std::uint32_t> index_;
    KeyMap<std::uint8_t> corners_;
};

GridPoint midpoint(const GridPoint& p, const GridPoint& q) {
    return {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
}

/// Appends to ring the leaf corners strictly inside the edge p → q, in order from p. A corner
/// inside an edge makes its midpoint a corner too (the cell of the next level holding it is
/// split, and its children meet at the midpoint), so the search descends only through corners.
void collect_edge(const VertexTable& table, const GridPoint& p, const GridPoint& q,
                  std::vector<GridPoint>& ring) {
    const GridPoint m = midpoint(p, q);
    if (m == p || !table.is_corner(m)) return;  // p == m: the edge is one unit long
    collect_edge(table, p, m, ring);
    ring.push_back(m);
    collect_edge(table, m, q, ring);
}

/// The sign of (b − a) · ((c − a) × (d − a)) for grid points: differences are exact in doubles,
/// and a tetrahedron of the mesh has a volume far above their rounding.
bool positively_oriented(const GridPoint& a, const GridPoint& b, const GridPoint& c,
                         const GridPoint& d) {
    auto diff = [&](const GridPoint& p) {
        return Vec3{static_cast<double>(p[0]) - static_cast<double>(a[0]),
                    static_cast<double>(p[1]) - static_cast<double>(a[1]),
                    static_cast<double>(p[2]) - static_cast<double>(a[2])};
    };
    return dot(diff(b), cross(diff(c), diff(d))) > 0.0;
}

/// The neighbour of leaf c across face d when it is finer than c (a cell of c's level with
/// children). Throws when the leaf there is coarser than c's parent: the tree is not balanced.
bool has_finer_neighbour(const Octree& tree, std::size_t c, int d) {
    const std::uint32_t n = tree.neighbour(c, d);
    if (n == Octree::no_cell) return false;
    const int level = tree.cell(c).level;
    if (tree.cell(n).level < level - 1)
        throw InvalidInput("tetrahedralize: the octree is not 2:1 balanced");
    return tree.cell(n).level == level && !tree.is_leaf(n);
}

}  // namespace

Tetrahedralization tetrahedralize(const Octree& tree) {
    if (tree.max_depth() > max_tetrahedralized_depth) {
        throw InvalidInput(fmt::format("tetrahedralize: octree depth {} exceeds {}",
                                       tree.max_depth(), max_tetrahedralized_depth));
    }
    Tetrahedralization mesh;
    VertexTable table(tree, mesh);
    const int shift = tree.max_depth() + 1;
    auto corner_of = [&](std::size_t c) {
        const auto& cell = tree.cell(c);
        const std::uint64_t u = std::uint64_t{1} << (shift - cell.level);
        return std::pair{GridPoint{cell.ix * u, cell.iy * u, cell.iz * u}, u};
    };
    for (std::size_t c = 0; c < tree.size(); ++c) {
        if (!tree.is_leaf(c)) continue;
        const auto [lo, u] = corner_of(c);
        for (std::uint64_t k = 0; k < 8; ++k)
            table.add_corner({lo[0] + (k & 1) * u, lo[1] + (k >> 1 & 1) * u, lo[2] + (k >> 2) * u});
    }
    mesh.cell_offsets.reserve(tree.size() + 1);
    mesh.cell_offsets.push_back(0);
    mesh.vertex_offsets.reserve(tree.size() + 1);
    mesh.vertex_offsets.push_back(0);
    std::vector<GridPoint> ring;
    std::vector<std::uint32_t> ids;
    for (std::size_t c = 0; c < tree.size(); ++c) {
        if (tree.is_leaf(c)) {
            const auto [lo, u] = corner_of(c);
            const GridPoint centre{lo[0] + u / 2, lo[1] + u / 2, lo[2] + u / 2};
            const std::uint32_t apex = table.at(centre);
            // Face d lies across axis a = d / 2 on the low (d even) or high side; its square
            // spans the two other axes b and e.
            for (int d = 0; d < 6; ++d) {
                const int a = d / 2, b = (a + 1) % 3, e = (a + 2) % 3;
                const std::uint64_t w = has_finer_neighbour(tree, c, d) ? u / 2 : u;
                for (std::uint64_t sb = 0; sb < u; sb += w) {
                    for (std::uint64_t se = 0; se < u; se += w) {
                        // The square [sb, sb + w] × [se, se + w] of the face, its corners in turn.
                        GridPoint corners[4];
                        for (int k = 0; k < 4; ++k) {
                            GridPoint p = lo;
                            p[a] += (d & 1) ? u : 0;
                            p[b] += sb + ((k == 1 || k == 2) ? w : 0);
                            p[e] += se + ((k >= 2) ? w : 0);
                            corners[k] = p;
                        }
                        ring.clear();
                        for (int k = 0; k < 4; ++k) {
                            ring.push_back(corners[k]);
                            collect_edge(table, corners[k], corners[(k + 1) % 4], ring);
                        }
                        const GridPoint face = midpoint(corners[0], corners[2]);
                        const std::uint32_t f = table.at(face);
                        // The ring's vertices in order: the order of first use of a fan's
                        // tetrahedra (apex, f, p, q), each looked up once.
                        ids.clear();
                        for (const GridPoint& p : ring) ids.push_back(table.at(p));
                        for (std::size_t k = 0; k < ring.size(); ++k) {
                            const std::size_t l = (k + 1) % ring.size();
                            std::array<std::uint32_t, 4> t{apex, f, ids[k], ids[l]};
                            if (!positively_oriented(centre, face, ring[k], ring[l]))
                                std::swap(t[2], t[3]);
                            mesh.tetrahedra.push_back(t);
                        }
                    }
                }
            }
        }
        mesh.cell_offsets.push_back(static_cast<std::uint32_t>(mesh.tetrahedra.size()));
        mesh.vertex_offsets.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
    }
    return mesh;
}

}  // namespace slc
