// The stages of contour() (paper §2), internal to the contour module: topology resolution on the
// triangulated tree (§2.1), the chain of contour vertices, and adaptive refinement (§2.2).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "checked_function.hpp"
#include "slc/contour/contour.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/core/box.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/tree/triangulation.hpp"

namespace slc::contouring {

/// The topology of the zero set (§2.1): the tree, its triangulation with G at every vertex
/// (|G| > η everywhere after perturbation), and which triangles G changes sign in.
struct Topology {
    Quadtree tree;
    Triangulation mesh;          ///< vertices moved where they were perturbed
    std::vector<double> values;  ///< G at mesh.vertices (stand-ins: see below)
    /// Vertices whose value is a stand-in with the right sign, never evaluated: centres of finest
    /// leaves that hold no zero under the gradient bound, and points the distance bound settled
    /// (ContourOptions::distance_slack). No triangle with a stand-in is crossed.
    std::vector<std::uint8_t> stand_in;
    std::vector<std::uint8_t> crossed;  ///< per triangle: G changes sign at its vertices
    double gamma = 1.0;                 ///< the gradient bound at which the tree balanced
    std::size_t thin_cells = 0;         ///< cells split beyond K where G bends
    bool thin_budget_reached = false;   ///< cells that bend left whole (thin_cell_budget)
    std::size_t perturbed = 0;          ///< vertices perturbed
    std::size_t settled = 0;            ///< tree points given stand-ins instead of evaluations of G
    std::size_t bound_evals = 0;        ///< evaluations of the bounds
};

/// Builds the K-level tree (γ doubled until balanced), triangulates it, perturbs vertices with
/// |G| ≤ η and checks that the zero set stays off the domain boundary. Throws NumericalFailure
/// naming the place when it does not, or when perturbation keeps failing.
/// bounds, when given, are the contour's cheap bounds on G.
Topology resolve_topology(BatchFunctionRef g, const Box& domain, const ContourOptions& options,
                          std::optional<BatchBoundsRef> bounds);

/// The zero set of the piecewise-linear interpolant: one vertex per triangle edge with a sign
/// change, one segment per crossed triangle, linked into closed polygons.
struct LinearContour {
    std::vector<Bracket> brackets;        ///< per vertex: its edge, lower vertex number first
    std::vector<std::uint32_t> next;      ///< segment i runs from vertex i to vertex next[i]
    std::vector<std::uint32_t> triangle;  ///< the triangle holding segment i
};

/// Marching triangles with G > 0 on the right of every segment. Marks topo.crossed.
LinearContour march(Topology& topo);

/// Closed polygons as doubly linked vertices, with the per-segment state refinement needs.
/// Segment i runs from vertex i to next[i]; removed vertices stay in the arrays, not alive.
struct Chain {
    std::vector<Vec2> points;
    std::vector<std::uint32_t> next, prev;
    std::vector<std::uint32_t> home;   ///< triangle segment i descends from (the safeguard's start)
    std::vector<double> mid_value;     ///< G at the midpoint of segment i; NaN until evaluated
    std::vector<std::uint8_t> frozen;  ///< a split of segment i was refused: do not retry it
    /// Segment i descends from a bridge that join_necks laid across the interpolant's false gap:
    /// its splits are not held to its home triangle.
    std::vector<std::uint8_t> unbound;
    std::vector<std::uint8_t> alive;
    std::vector<std::uint32_t> curve;     ///< the curve of vertex i
    std::vector<std::size_t> curve_size;  ///< alive vertices per curve
    /// |segment i|, kept up to date by insert_after and remove: refinement asks for each
    /// segment's length several times a pass.
    std::vector<double> lengths;

    Chain(std::vector<Vec2> vertices, std::span<const std::uint32_t> successor,
          std::span<const std::uint32_t> triangle);
    Segment segment(std::uint32_t i) const { return {points[i], points[next[i]]}; }
    double length(std::uint32_t i) const { return lengths[i]; }
    /// Adds vertex w on segment u; both halves keep u's home and are not yet evaluated.
    std::uint32_t insert_after(std::uint32_t u, Vec2 w);
    /// Removes vertex x; the merged segment takes the home of the longer of x's two segments.
    void remove(std::uint32_t x);
    /// The alive polygons, each from its lowest-numbered vertex: deterministic.
    Interface to_interface() const;
};

/// Segments of a Chain bucketed on a uniform grid, for exact crossing tests of new segments
/// against their neighbourhood. Entries go stale when the chain changes and are skipped.
///
/// The buckets are one hash table of chains threaded through a single entry array (no
/// allocation per cell or per entry); the order of a bucket never matters, since its users ask
/// whether any segment crosses, or for the least hit distance.
class SegmentGrid {
public:
    SegmentGrid(const Chain& chain, double cell);
    /// Registers segment u as it now is.
    void insert(std::uint32_t u);
    /// True if s meets a current segment other than those starting at a vertex in skip.
    bool crosses(Segment s, std::span<const std::uint32_t> skip) const;
    /// Distance from o along the unit direction d to the first current segment other than
    /// segment skip that the ray meets within reach; infinity if none.
    double first_hit(Vec2 o, Vec2 d, double reach, std::uint32_t skip) const {
        return first_hit_segment(o, d, reach, skip).first;
    }
    /// The same distance and the segment hit (none when nothing is).
    std::pair<double, std::uint32_t> first_hit_segment(Vec2 o, Vec2 d, double reach,
                                                       std::uint32_t skip) const;
    static constexpr std::uint32_t none = 0xffffffffu;

private:
    /// Segment u → next[u] as registered, in the cell with the given key.
    struct Entry {
        std::uint64_t key;
        std::uint32_t u, v;
        std::uint32_t next;  ///< the bucket's next entry, or none
    };

    std::uint64_t key(std::int64_t ix, std::int64_t iy) const;
    /// The cells [x0, x1] × [y0, y1] that a bounding box covers.
    std::array<std::int64_t, 4> cell_range(const Box& b) const;
    std::uint32_t bucket(std::uint64_t key) const;
    void add(std::uint64_t key, std::uint32_t u, std::uint32_t v);
    /// Calls f(u) for every current segment u registered in the cells that box b covers (stale
    /// entries skipped), until f returns true; returns whether one did.
    template <class F>
    bool any_in_cells(const Box& b, F&& f) const {
        const auto [x0, y0, x1, y1] = cell_range(b);
        for (std::int64_t iy = y0; iy <= y1; ++iy) {
            for (std::int64_t ix = x0; ix <= x1; ++ix) {
                const std::uint64_t k = key(ix, iy);
                for (std::uint32_t e = heads_[bucket(k)]; e != none; e = entries_[e].next) {
                    const Entry& entry = entries_[e];
                    if (entry.key != k || !chain_.alive[entry.u] || chain_.next[entry.u] != entry.v)
                        continue;
                    if (f(entry.u)) return true;
                }
            }
        }
        return false;
    }

    const Chain& chain_;
    double cell_;
    Vec2 origin_;
    std::vector<std::uint32_t> heads_;  ///< first entry of each bucket; size a power of two
    std::vector<Entry> entries_;
};

/// What refinement did.
struct RefineReport {
    int passes = 0;
    std::size_t splits = 0;
    std::size_t rejected = 0;
    std::size_t pruned = 0;
    std::size_t parted = 0;  ///< bridges parted (part_bridges)
    std::optional<double> max_midpoint_value;
};

/// Joins curves that the interpolant parted where G does not: two curves of one orientation
/// within a finest cell edge of each other, with G at the midpoint of their nearest vertices of
/// the sign they enclose (a thin tip cut off from its body, say), become one, by two bridges
/// in place of their facing segments, when the bridges cross no segment. One batch of G.
/// Returns the number of joins.
std::size_t join_necks(Chain& chain, BatchFunctionRef g, const Topology& topo,
                       const ContourOptions& options);

/// Parts what the interpolant joined where G does not, the converse of join_necks: two parts a
/// gap narrower than a cell apart whose triangles the interpolant links across the gap by a strip
/// of their own sign, so that one curve goes round both. Offered are the segments in `rootless`,
/// whose midpoint missed ε and whose bracket found no zero: for each, the first segment of its
/// curve that its bracket's ray meets within its home triangle's longest edge, when that one
/// runs the opposite way with its midpoint's G not of the other sign; G at the centre of the two
/// segments' four ends, one batch. Where G there has the sign of the midpoints (the strip between
/// them is G's other side, not the interpolant's) and |G| > η, the two segments u → next u and
/// v → next v become u → next v and v → next u, when these cross no segment and each other not,
/// and the curve parts into two loops side by side, each oriented as it was and at least a
/// quarter of a K-level cell thick (2|A|/L). A hole (a strip crossing a wall) or a thinner loop
/// is left for the time loop's deeper thin cells. `segments` is refinement's grid of the chain,
/// kept current. Returns the number parted.
std::size_t part_bridges(Chain& chain, SegmentGrid& segments, BatchFunctionRef g,
                         const Topology& topo, std::span<const std::uint32_t> rootless,
                         const ContourOptions& options);

/// P passes of split, bracket, root-find, safeguard and prune (§2.2) on the chain.
RefineReport refine(Chain& chain, BatchFunctionRef g, const Topology& topo, const Box& domain,
                    const ContourOptions& options);

}  // namespace slc::contouring
