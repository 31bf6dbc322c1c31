/// @file
/// The parameters of contouring (paper Table 4; DESIGN §4), one type for curves and surfaces:
/// ContourOptions (contour.hpp) is BasicContourOptions<2> and SurfaceContourOptions
/// (surface_contour.hpp) BasicContourOptions<3>. The names, types and defaults are the same in both
/// but for the depth K and the vertex cap; ρ and the triangle safeguard are the curves' own,
/// creases the surfaces' own (the other dimension refuses them set), and η unset resolves by each
/// dimension's rule (resolved_eta).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

#include "slc/contour/root_finding.hpp"

namespace slc {

/// A shape's topology as the runs' checks and slc contour compare it: its components (curves, or
/// a surface's closed components) and its holes (clockwise curves) or handles (a surface's genus).
struct ShapeTopology {
    std::size_t components = 0;
    long long holes = 0;
    bool operator==(const ShapeTopology&) const = default;
};

/// The contour options of dimension dim (2 or 3).
template <int dim>
struct BasicContourOptions {
    /// refine_passes value meaning: refine until no midpoint (for a surface, no edge midpoint or
    /// centroid) exceeds ε, or a pass changes nothing, but at most max_refine_passes passes.
    static constexpr int until_converged = -1;
    /// η when none is given: the linear contour's vertices on the zero set to 10⁻¹⁰.
    static constexpr double default_eta = 1e-10;

    /// K: deepest level of the topology tree (6 for curves, 5 for surfaces), 0 up to the deepest
    /// level the dimension's tree takes (Quadtree::max_supported_depth,
    /// max_tetrahedralized_depth).
    int depth = dim == 2 ? 6 : 5;
    /// P ≥ 0, or until_converged: passes of adaptive refinement (§2.2); 0 is the linear contour.
    /// Refinement also stops early when nothing exceeds ε or a pass changes nothing, so a large P
    /// runs to convergence too.
    int refine_passes = 0;
    /// ε ≥ η: refinement splits segments whose midpoint (for a surface: edges whose midpoint and
    /// triangles whose centroid) has |G| > ε; default 10^−K. For curves neither ε nor η can go
    /// below what doubles resolve in the domain, two ulps of its largest coordinate: a given ε
    /// below it is InvalidInput, the default 10^−K and η are raised to it.
    std::optional<double> eps = std::nullopt;
    /// η > 0: root-finding tolerance, |G| ≤ η at every vertex; mesh vertices with |G| ≤ η are
    /// moved off zero. Unset (the default): each dimension's resolved_eta.
    std::optional<double> eta = std::nullopt;
    /// Levels beyond K, 0 up to the deepest level less K, for cells at depth K near the zero set
    /// where G bends within the cell — its centre nearer zero than the mean of the ends of a
    /// (body) diagonal by more than a quarter of the half-diagonal, all three of one sign, which
    /// a distance does not do on one side of a curve or sheet turning less than about two cells:
    /// a thin part, two parts in near contact, a corner, a sharp edge or a tight turn. Such cells
    /// split again, up to K + thin_depth, so that the linear contour has both sides of what it
    /// would otherwise miss or cut across. 0 (the default) keeps every leaf at depth K or above;
    /// Enright's test, whose sheet thins below a cell, takes 2 (docs/surfaces.md).
    int thin_depth = 0;
    /// Curves: whether that test also reads the grid lines through the centres of coarser cells,
    /// as a surface's always does. It finds a part thinner than a cell that crosses a cell beside
    /// a corner, where no diagonal dips: a sharp tip, cut across without it. On for a distance and
    /// for a flow field's step, whose G is a distance carried by the flow; the steps of normal and
    /// curvature laws turn it off, since their G keeps loops smaller than a cell beyond sharp
    /// tips, which these lines would find and resolve as parts the law forbids.
    bool bends_through_centres = true;
    /// Curves: ρ in [0, 1): prune segments shorter than ρ times both neighbours; 0 disables
    /// pruning.
    double rho = 0.1;
    /// γ > 0: starting estimate of the gradient bound |∇G| ≤ γ, doubled until the tree balances.
    double gamma = 1.0;
    /// Cap on the passes of until_converged.
    int max_refine_passes = 64;
    /// Refinement that would pass this many vertices throws LimitExceeded naming ε (about 100
    /// bytes a vertex of a curve: 420 MB). A smooth curve of length L and curvature κ refined to
    /// ε needs about L·sqrt(κ/8ε) vertices: 2.2e7 for the unit circle at ε = 1e−14.
    std::size_t max_vertices = std::size_t{1} << (dim == 2 ? 22 : 23);
    /// Curves: the paper's triangle safeguard. A vertex added by refinement may stay in its
    /// segment's triangle or move into an adjacent one where G has no sign change, no farther.
    /// Off, it may go as far as its bracket reaches (at most three segment lengths, and short of
    /// every other segment), the angle and crossing safeguards still keeping every curve simple
    /// and apart: refinement then finds the corners of the zero set that the tree's triangles cut
    /// off.
    bool triangle_safeguard = true;
    /// Curves: refinement parts what the safeguards would keep joined where G says the parts are
    /// two: two parts a gap narrower than a cell apart that the interpolant links across the gap
    /// (docs/algorithms/contour.md, "Parting what the interpolant joined"). Off, the refined
    /// contour keeps the interpolant's topology, as the paper's safeguards do (its Fig. 8).
    bool part_bridges = true;
    /// Surfaces: refinement follows creases and corners, for G the distance of a surface of flat
    /// facets (a user's mesh). Before each splitting pass, the triangles beyond ε are cut where
    /// the zero set's planes at their corners meet (G's gradient by differences), so that each
    /// child lies in one plane; folds of the linear contour across a crease are triangulated
    /// again in its planes; an edge whose profile along the normal is two lines is split where
    /// they meet. Should that leave a part beyond ε, plain refinement of the linear contour is
    /// kept instead if it comes nearer. Off (the default) for the steps of a run, whose G rounds
    /// what a crease would sharpen (docs/surfaces.md).
    bool creases = false;
    /// How brackets are shrunk: Brent (default), Illinois, or the paper's bisection.
    RootMethod root_method = RootMethod::brent;
    /// δ ≥ 0, when the caller can guarantee |G(x) − G(y)| ≤ |x − y| + δ for all x and y: 0 for a
    /// signed distance function, 2k·max|W| for the semi-Lagrangian formula. Tree points where a
    /// nearby sample's value already bounds |G| above the split threshold are then not evaluated
    /// (the bound, with its certain sign, stands in), so cells far from the zero set cost no
    /// evaluation. The contour is the one exact values give, bit for bit. Unset (the default):
    /// every tree point is evaluated.
    std::optional<double> distance_slack = std::nullopt;
    /// Surfaces: the components and handles of the shape whose distance G is (a user's mesh),
    /// when known. Beside a sharp edge or point of the shape, the signs of G at the mesh's
    /// vertices can cut a speck off a corner or open a handle along an edge that the shape does
    /// not have, at any depth: a vertex a hair from the zero set (within a sixteenth of the
    /// finest cell) decides it. Where the linear contour's components or handles differ from
    /// these, such vertices that are not simple (whose side changes the contour's topology) are
    /// moved across the zero set, one at a time and by at most a tenth of the finest cell,
    /// where that brings the contour nearer the shape, until it has the shape's (else none is
    /// moved: a part thinner than the cells is not a sharp edge). The contour's vertices are
    /// still roots of G and the mesh stays valid, as in perturbation. Unset (the default) for the
    /// steps of a run and the named problems.
    std::optional<ShapeTopology> keep_topology = std::nullopt;

    /// ε as given, or its default 10^−K.
    double resolved_eps() const { return eps.value_or(std::pow(10.0, -depth)); }
    /// η as given; unset, default_eta for curves and for a surface's linear contour (P = 0), and
    /// max(default_eta, ε/100) when a surface's refinement follows. Refinement holds G within ε
    /// at every edge midpoint and centroid, so vertices within ε/100 change the surface's error
    /// by at most a hundredth of ε, and roots found to that tolerance rather than 10⁻¹⁰ cost
    /// about one evaluation of G fewer per split (docs/tables/table3_3d.md).
    double resolved_eta() const {
        if (eta) return *eta;
        if (dim == 2 || refine_passes == 0) return default_eta;
        return std::max(default_eta, resolved_eps() / 100.0);
    }
};

}  // namespace slc
