// Conforming tetrahedral mesh of a balanced octree: cones from leaf centres over fans of faces.
#include "slc/tree/tetrahedralization.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <limits>
#include <utility>

#include "finer_neighbour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

using GridPoint = std::array<std::uint64_t, 3>;

/// Whether grid point p is a corner of a leaf, read from the tree. p is a corner of cells of
/// every level whose lattice holds it, from the coarsest, ℓ, on; it is a leaf's corner when one
/// of the (up to eight) cells of level ℓ around it is in the tree: that cell's descendants down
/// to a leaf keep p as a corner, and a leaf with corner p has such an ancestor. O(8 ℓ), the
/// top of the tree read again each time (it stays in cache).
bool is_leaf_corner(const Octree& tree, const GridPoint& p) {
    const int shift = tree.max_depth() + 1;  // a cell of level ℓ is 2^(shift − ℓ) grid units
    const int zeros = std::countr_zero(p[0] | p[1] | p[2] | (std::uint64_t{1} << shift));
    const int level = shift - zeros;
    if (level > tree.max_depth()) return false;  // odd: a cell's centre, no corner
    for (int k = 0; k < 8; ++k) {
        std::array<std::int64_t, 3> at{};
        for (int i = 0; i < 3; ++i)
            at[i] = static_cast<std::int64_t>(p[i] >> zeros) - ((k >> i) & 1);
        const std::uint32_t c = tree.find(level, at);
        if (c != Octree::no_cell && tree.cell(c).level == level) return true;
    }
    return false;
}

GridPoint midpoint(const GridPoint& p, const GridPoint& q) {
    return {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
}

/// Appends to ring the leaf corners strictly inside the edge p → q, in order from p. A corner
/// inside an edge makes its midpoint a corner too (the cell of the next level holding it is
/// split, and its children meet at the midpoint), so the search descends only through corners.
void collect_edge(const Octree& tree, const GridPoint& p, const GridPoint& q,
                  std::vector<GridPoint>& ring) {
    const GridPoint m = midpoint(p, q);
    if (m == p || !is_leaf_corner(tree, m)) return;  // p == m: the edge is one unit long
    collect_edge(tree, p, m, ring);
    ring.push_back(m);
    collect_edge(tree, m, q, ring);
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

/// What tetrahedralize() throws for an octree that is not 2:1 balanced (Octree::is_balanced,
/// checked once before any leaf; has_finer_neighbour checks it again where it looks).
constexpr const char* unbalanced = "tetrahedralize: the octree is not 2:1 balanced";

/// The low corner of cell c on the grid of half the finest edge, and its edge there.
std::pair<GridPoint, std::uint64_t> low_corner(const Octree& tree, std::size_t c) {
    const auto& cell = tree.cell(c);
    const std::uint64_t u = std::uint64_t{1} << (tree.max_depth() + 1 - cell.level);
    return {GridPoint{cell.coords[0] * u, cell.coords[1] * u, cell.coords[2] * u}, u};
}

/// One leaf's tetrahedra over its own list of vertices: their keys in order of first use, and
/// each tetrahedron as four places in that list.
struct LeafTetrahedra {
    std::vector<std::uint64_t> keys;
    std::vector<std::array<std::uint16_t, 4>> tetrahedra;

    /// The place of grid point p in keys, added at the end when new.
    std::uint16_t at(const GridPoint& p) {
        const std::uint64_t k = Tetrahedralization::key(p[0], p[1], p[2]);
        for (std::size_t i = keys.size(); i-- > 0;)
            if (keys[i] == k) return static_cast<std::uint16_t>(i);
        if (keys.size() == std::numeric_limits<std::uint16_t>::max() + std::size_t{1})
            throw InvalidInput("tetrahedralize: a leaf has more than 65536 vertices");
        keys.push_back(k);
        return static_cast<std::uint16_t>(keys.size() - 1);
    }
};

/// Whether the edge p → q of a leaf (low corner lo, edge u) may hold corners of finer leaves:
/// whether its bit is set among the leaf's finer_sides().
bool edge_touched(std::uint32_t sides, const GridPoint& lo, std::uint64_t u, const GridPoint& p,
                  const GridPoint& q) {
    int a = 0;
    while (p[a] == q[a]) ++a;
    const int b = (a + 1) % 3, e = (a + 2) % 3;
    const int k = static_cast<int>((p[b] - lo[b]) / u + 2 * ((p[e] - lo[e]) / u));
    return (sides >> edge_side(a, k) & 1u) != 0;
}

/// Appends the cones of the leaf with low corner lo and edge u to out: for each face (or
/// quarter, where finer(d) says the neighbour across face d is finer) a fan from its centre over
/// its ring, each cone from the leaf's centre. The ring holds the square's corners and what
/// collect(p, q, quarter, ring) appends of the leaf corners inside its edge p → q (quarter: the
/// square is a quarter of the face).
template <class Finer, class Collect>
void cones(const GridPoint& lo, std::uint64_t u, Finer&& finer, Collect&& collect,
           LeafTetrahedra& out) {
    const GridPoint centre{lo[0] + u / 2, lo[1] + u / 2, lo[2] + u / 2};
    const std::uint16_t apex = out.at(centre);
    thread_local std::vector<GridPoint> ring;
    thread_local std::vector<std::uint16_t> ids;
    // Face d lies across axis a = d / 2 on the low (d even) or high side; its square spans the
    // two other axes b and e.
    for (int d = 0; d < 6; ++d) {
        const int a = d / 2, b = (a + 1) % 3, e = (a + 2) % 3;
        const std::uint64_t w = finer(d) ? u / 2 : u;
        for (std::uint64_t sb = 0; sb < u; sb += w) {
            for (std::uint64_t se = 0; se < u; se += w) {
                // The square [sb, sb + w] × [se, se + w] of the face, its corners in turn.
                GridPoint square[4];
                for (int k = 0; k < 4; ++k) {
                    GridPoint p = lo;
                    p[a] += (d & 1) ? u : 0;
                    p[b] += sb + ((k == 1 || k == 2) ? w : 0);
                    p[e] += se + ((k >= 2) ? w : 0);
                    square[k] = p;
                }
                ring.clear();
                for (int k = 0; k < 4; ++k) {
                    ring.push_back(square[k]);
                    collect(square[k], square[(k + 1) % 4], w < u, ring);
                }
                const GridPoint face = midpoint(square[0], square[2]);
                const std::uint16_t f = out.at(face);
                ids.clear();
                for (const GridPoint& p : ring) ids.push_back(out.at(p));
                for (std::size_t k = 0; k < ring.size(); ++k) {
                    const std::size_t l = (k + 1) % ring.size();
                    std::array<std::uint16_t, 4> t{apex, f, ids[k], ids[l]};
                    if (!positively_oriented(centre, face, ring[k], ring[l])) std::swap(t[2], t[3]);
                    out.tetrahedra.push_back(t);
                }
            }
        }
    }
}

/// Appends leaf c's cones to out. sides: c's finer_sides(), which spare the search of the edges
/// no finer cell touches.
void cones_of_leaf(const Octree& tree, std::size_t c, std::uint32_t sides, LeafTetrahedra& out) {
    const auto [lo, u] = low_corner(tree, c);
    cones(
        lo, u, [&](int d) { return has_finer_neighbour(tree, c, d, unbalanced); },
        [&](const GridPoint& p, const GridPoint& q, bool quarter, std::vector<GridPoint>& ring) {
            if (quarter || edge_touched(sides, lo, u, p, q)) collect_edge(tree, p, q, ring);
        },
        out);
}

/// The cones of a leaf that no finer cell touches (finer_sides() 0), which are those of every
/// such leaf moved and scaled: 15 vertices and 24 tetrahedra, from cones() on the leaf of edge 2
/// at the grid's origin. A leaf's vertices are its low corner plus these offsets times half its
/// edge.
struct UntouchedLeaf {
    std::vector<GridPoint> offsets;
    std::vector<std::array<std::uint16_t, 4>> tetrahedra;

    UntouchedLeaf() {
        LeafTetrahedra unit;
        cones(
            GridPoint{0, 0, 0}, 2, [](int) { return false; },
            [](const GridPoint&, const GridPoint&, bool, std::vector<GridPoint>&) {}, unit);
        constexpr std::uint64_t mask = (std::uint64_t{1} << 21) - 1;
        for (const std::uint64_t k : unit.keys)
            offsets.push_back({k >> 42, k >> 21 & mask, k & mask});
        tetrahedra = std::move(unit.tetrahedra);
    }
    /// Appends leaf c's cones to out, as cones_of_leaf() would.
    void append(const Octree& tree, std::size_t c, LeafTetrahedra& out) const {
        const auto [lo, u] = low_corner(tree, c);
        const std::uint64_t half = u / 2;
        for (const GridPoint& o : offsets) {
            out.keys.push_back(Tetrahedralization::key(lo[0] + o[0] * half, lo[1] + o[1] * half,
                                                       lo[2] + o[2] * half));
        }
        out.tetrahedra.insert(out.tetrahedra.end(), tetrahedra.begin(), tetrahedra.end());
    }
};

/// A hash of a key for sorting keys into buckets, unlike KeyMap's (the top bits of the key
/// times 2^64/φ), so that each bucket's own KeyMap spreads its keys.
std::size_t bucket_of(std::uint64_t key, int bits) {
    key ^= key >> 31;
    key *= 0xBF58476D1CE4E5B9ull;
    key ^= key >> 29;
    return static_cast<std::size_t>(key >> (64 - bits));
}

}  // namespace

std::vector<std::uint32_t> finer_sides(const Octree& tree) {
    std::vector<std::uint32_t> sides(tree.size(), 0);
    auto mark = [&](std::uint32_t n, int level, int side) {
        if (n != Octree::no_cell && tree.cell(n).level == level && tree.is_leaf(n))
            sides[n] |= std::uint32_t{1} << side;
    };
    // Each split cell p marks the leaves of its level across its faces, and around its edges:
    // the two across the faces that meet there and the one diagonally across.
    for (std::size_t p = 0; p < tree.size(); ++p) {
        if (tree.is_leaf(p)) continue;
        const int level = tree.cell(p).level;
        std::array<std::uint32_t, 6> across{};
        for (int d = 0; d < 6; ++d) {
            across[d] = tree.neighbour(p, d);
            mark(across[d], level, d ^ 1);
        }
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, e = (a + 2) % 3;
            for (int k = 0; k < 4; ++k) {
                const int high_b = k & 1, high_e = k >> 1;
                const std::uint32_t qb = across[2 * b + high_b], qe = across[2 * e + high_e];
                mark(qb, level, edge_side(a, k ^ 1));
                mark(qe, level, edge_side(a, k ^ 2));
                // Balanced, the tree has the cells of p's level across p's faces (p's children
                // would otherwise border a leaf two levels coarser), unless they lie beyond the
                // root box, where the diagonal does too.
                if (qb != Octree::no_cell && tree.cell(qb).level == level)
                    mark(tree.neighbour(qb, 2 * e + high_e), level, edge_side(a, k ^ 3));
            }
        }
    }
    return sides;
}

Tetrahedralization tetrahedralize(const Octree& tree, std::span<const std::uint8_t> wanted,
                                  std::span<const std::uint32_t> sides) {
    if (tree.max_depth() > max_tetrahedralized_depth) {
        throw InvalidInput(fmt::format("tetrahedralize: octree depth {} exceeds {}",
                                       tree.max_depth(), max_tetrahedralized_depth));
    }
    if (!wanted.empty() && wanted.size() != tree.size())
        throw InvalidInput("tetrahedralize: one flag a cell is wanted");
    // (Leaves that no finer cell touches take their cones from UntouchedLeaf, which sees no
    // neighbour: the balance is checked here for all.)
    if (!tree.is_balanced()) throw InvalidInput(unbalanced);
    const std::size_t cells = tree.size();
    if (!sides.empty() && sides.size() != cells)
        throw InvalidInput("tetrahedralize: one set of finer sides a cell");
    std::vector<std::uint32_t> own_sides;
    if (sides.empty()) {
        own_sides = finer_sides(tree);
        sides = own_sides;
    }
    const int shift = tree.max_depth() + 1;
    // Each leaf's cones over its own vertices, on all threads, in blocks of cells.
    static const UntouchedLeaf untouched;
    constexpr std::size_t block = 64;
    const std::size_t blocks = (cells + block - 1) / block;
    std::vector<LeafTetrahedra> made(blocks);
    std::vector<std::uint32_t> key_count(cells + 1, 0), tetrahedron_count(cells + 1, 0);
    parallel_for(
        blocks,
        [&](std::size_t b) {
            LeafTetrahedra& out = made[b];
            for (std::size_t c = b * block; c < std::min(cells, (b + 1) * block); ++c) {
                if (!tree.is_leaf(c) || (!wanted.empty() && !wanted[c])) continue;
                thread_local LeafTetrahedra leaf;
                leaf.keys.clear();
                leaf.tetrahedra.clear();
                if (sides[c] == 0)
                    untouched.append(tree, c, leaf);
                else
                    cones_of_leaf(tree, c, sides[c], leaf);
                key_count[c + 1] = static_cast<std::uint32_t>(leaf.keys.size());
                tetrahedron_count[c + 1] = static_cast<std::uint32_t>(leaf.tetrahedra.size());
                out.keys.insert(out.keys.end(), leaf.keys.begin(), leaf.keys.end());
                out.tetrahedra.insert(out.tetrahedra.end(), leaf.tetrahedra.begin(),
                                      leaf.tetrahedra.end());
            }
        },
        1);
    // Every leaf's vertex keys in one list, leaf after leaf ("uses"); key_count becomes the
    // offsets of the leaves' uses and tetrahedron_count those of their tetrahedra.
    for (std::size_t c = 0; c < cells; ++c) {
        key_count[c + 1] += key_count[c];
        tetrahedron_count[c + 1] += tetrahedron_count[c];
    }
    const std::size_t uses = key_count[cells];
    std::vector<std::uint64_t> key(uses);
    parallel_for(
        blocks,
        [&](std::size_t b) {
            std::copy(made[b].keys.begin(), made[b].keys.end(), key.begin() + key_count[b * block]);
        },
        1);
    // The first use of each key: the uses sorted into buckets by key, each bucket's in order,
    // on all threads; first[i] is the first use of use i's key.
    constexpr int bucket_bits = 10;
    const Buckets buckets = counting_sort(uses, std::size_t{1} << bucket_bits, [&](std::size_t i) {
        return bucket_of(key[i], bucket_bits);
    });
    std::vector<std::uint32_t> first(uses);
    parallel_for(
        std::size_t{1} << bucket_bits,
        [&](std::size_t b) {
            KeyMap<std::uint32_t> seen(buckets.start[b + 1] - buckets.start[b]);
            for (std::uint32_t k = buckets.start[b]; k < buckets.start[b + 1]; ++k) {
                const std::uint32_t i = buckets.items[k];
                first[i] = *seen.try_emplace(key[i], i).first;
            }
        },
        1);
    // The vertices, numbered in order of first use: leaf after leaf, each leaf's new keys in
    // their order there.
    Tetrahedralization mesh;
    mesh.vertex_offsets.assign(cells + 1, 0);
    parallel_for(cells, [&](std::size_t c) {
        std::uint32_t fresh = 0;
        for (std::uint32_t i = key_count[c]; i < key_count[c + 1]; ++i) fresh += first[i] == i;
        mesh.vertex_offsets[c + 1] = fresh;
    });
    for (std::size_t c = 0; c < cells; ++c) mesh.vertex_offsets[c + 1] += mesh.vertex_offsets[c];
    const std::size_t vertices = mesh.vertex_offsets[cells];
    mesh.vertices.resize(vertices);
    mesh.grid.resize(vertices);
    std::vector<std::uint32_t> id(uses);
    const Vec3 origin = tree.root_box().lo;
    const double step = tree.edge(0) / static_cast<double>(std::uint64_t{1} << shift);
    parallel_for(cells, [&](std::size_t c) {
        std::uint32_t v = mesh.vertex_offsets[c];
        for (std::uint32_t i = key_count[c]; i < key_count[c + 1]; ++i) {
            if (first[i] != i) continue;
            constexpr std::uint64_t mask = (std::uint64_t{1} << 21) - 1;
            const std::array<std::uint32_t, 3> g{static_cast<std::uint32_t>(key[i] >> 42),
                                                 static_cast<std::uint32_t>(key[i] >> 21 & mask),
                                                 static_cast<std::uint32_t>(key[i] & mask)};
            mesh.grid[v] = g;
            mesh.vertices[v] = {origin.x + static_cast<double>(g[0]) * step,
                                origin.y + static_cast<double>(g[1]) * step,
                                origin.z + static_cast<double>(g[2]) * step};
            id[i] = v++;
        }
    });
    parallel_for(uses, [&](std::size_t i) {
        if (first[i] != i) id[i] = id[first[i]];
    });
    // The tetrahedra, each leaf's at its place.
    mesh.cell_offsets = std::move(tetrahedron_count);
    mesh.tetrahedra.resize(mesh.cell_offsets[cells]);
    parallel_for(
        blocks,
        [&](std::size_t b) {
            const std::array<std::uint16_t, 4>* local = made[b].tetrahedra.data();
            for (std::size_t c = b * block; c < std::min(cells, (b + 1) * block); ++c) {
                const std::uint32_t* ids = id.data() + key_count[c];
                for (std::uint32_t t = mesh.cell_offsets[c]; t < mesh.cell_offsets[c + 1]; ++t) {
                    const std::array<std::uint16_t, 4>& l = *local++;
                    mesh.tetrahedra[t] = {ids[l[0]], ids[l[1]], ids[l[2]], ids[l[3]]};
                }
            }
        },
        1);
    return mesh;
}

}  // namespace slc
