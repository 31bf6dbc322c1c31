// The topology tree of contouring (paper §2.1), written once for curves (dim = 2) and surfaces
// (dim = 3, DESIGN §8), internal to the contour module: G sampled at the corners and centres of
// the tree's cells with stand-ins where bounds give its sign, and the tree split by min|G|
// against γ·edge with γ doubled until it is 2:1 balanced. topology.cpp (triangles) and
// surface_contour.cpp (tetrahedra) add what their simplices need.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "slc/contour/implicit_function.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/space.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc::contouring {

/// After this many doublings of γ (a factor of about 10^7) the tree is balanced by brute force
/// instead: G has a gradient far beyond any estimate, or no useful one.
inline constexpr int max_gamma_doublings = 24;
/// G bends within a cell (TreeSampler::bends) when the middle of three equally spaced samples on
/// a line is nearer zero than the ends' mean by this fraction of half their span.
inline constexpr double thin_dip = 0.25;

/// Integer coordinates on the grid of half the finest cell edge, from the root box's low corner
/// (the triangulation and the tetrahedralization name their vertices by them), and the points
/// there by the formula both place their vertices with: the mesh's vertices are the sample points
/// themselves, and G is never evaluated twice at one point.
template <int dim>
class SampleGrid {
public:
    using Point = PointOf<dim>;                     ///< Vec2 or Vec3
    using Coords = std::array<std::uint64_t, dim>;  ///< a grid point
    static constexpr int key_bits = 64 / dim;       ///< bits of each coordinate in a key

    explicit SampleGrid(const Orthtree<dim>& tree)
        : lo_(tree.root_box().lo),
          shift_(tree.max_depth() + 1),
          step_(tree.edge(0) / static_cast<double>(std::uint64_t{1} << shift_)) {}

    /// A cell's edge at the given level, in grid units.
    std::uint64_t units(int level) const { return std::uint64_t{1} << (shift_ - level); }
    /// The root's edge in grid units.
    std::uint64_t extent() const { return std::uint64_t{1} << shift_; }
    /// The point at grid point g.
    Point point(const Coords& g) const {
        Point p = lo_;
        for (int i = 0; i < dim; ++i) p[i] += static_cast<double>(g[i]) * step_;
        return p;
    }
    /// The key of g: x in the high bits, then y (, z), key_bits each (as
    /// Tetrahedralization::key in space).
    static std::uint64_t key(const Coords& g) {
        std::uint64_t k = 0;
        for (int i = 0; i < dim; ++i) k = (k << key_bits) | g[i];
        return k;
    }

private:
    Point lo_;
    int shift_;
    double step_;
};

/// Where a sample's value comes from: G itself, or a stand-in from the parent's samples or from
/// the caller's bounds (after which only G can tighten it).
enum class Source : std::uint8_t { g, parents, bounds };

/// G at a point, or a stand-in: a lower bound on |G| with G's sign, and an upper bound.
struct Sample {
    double value;  ///< G, or a stand-in with G's sign; NaN while pending
    double upper;  ///< |G| ≤ upper: |value| when exact
    Source source;
    std::uint32_t vertex = 0xffffffffu;  ///< its number in the triangulation, once numbered

    /// True when value is G there.
    bool is_exact() const { return source == Source::g && !std::isnan(value); }
};

/// A point in the batch for G.
inline constexpr Sample pending{std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity(), Source::g};

/// G at the corners and centres of the tree's cells, each point evaluated at most once, in one
/// batch per call, and the smallest |G| over each cell's sample points. γ tests cells down to
/// level `limit` (the tree's depth limit in the plane; K in space, where thin cells go deeper).
/// In the plane the centres of cells at the depth limit, never tested, wait for the caller
/// (centres_at_depth_limit).
///
/// A point is evaluated only when a split test, the sign of a simplex or root finding needs G
/// there. With a distance slack δ, |G(x) − G(y)| ≤ |x − y| + δ, so a new point x near a known
/// sample y has |G(y)| − |x − y| − δ ≤ |G(x)| ≤ |G(y)| + |x − y| + δ and, when the lower bound
/// exceeds η, G(y)'s sign; the caller's bounds on G, one batch, are tried next. Where either
/// gives the sign, the lower bound with that sign stands in for G, beside the upper bound. A
/// cell's test needs no value where some sample's upper bound is below its threshold γ·edge (it
/// splits), nor where a stand-in's lower bound reaches it; the stand-ins it does need are offered
/// to the bounds, then evaluated. So every split decision is the one exact values give, and
/// stand-ins left in simplices where G changes sign are evaluated before the contour is marched.
///
/// The samples live in one array, and every cell keeps the ids of its samples, so the split
/// tests, the donors and the mesh read them without a search. A new cell's corners are its
/// parent's corners and centre, or points on its parent's faces, which a neighbour's children may
/// share: only those are looked up in a table of keys. A cell's centre is its own (its children's
/// corners reach it through their parent). The new points' stand-ins are worked out on all
/// threads, each from the parent of the first cell that meets it, so they are the same for any
/// thread count.
template <int dim>
class TreeSampler {
public:
    using Point = PointOf<dim>;  ///< Vec2 or Vec3
    using Tree = Orthtree<dim>;
    using FunctionRef = BatchRef<double, Point>;  ///< G
    using BoundsRef = BatchRef<Interval, Point>;  ///< bounds on G
    /// Sample points of a cell: its corners (child order: bit i of j high along axis i), then
    /// its centre.
    static constexpr std::size_t cell_points = Tree::children + 1;
    /// Whether cells at the tree's depth limit sample their centres with their corners: in
    /// space, for the thin-cell test; in the plane a leaf's centre there waits for the gradient
    /// bound (CurveSampler::complete_centres).
    static constexpr bool centres_at_depth_limit = dim == 3;
    /// Whether centres are in the table of keys: in space the tetrahedra's vertices are looked
    /// up there (SurfaceSampler::at); in the plane a centre is reached through its cell.
    static constexpr bool centres_in_table = dim == 3;
    /// In the plane: whether a cell's centre is entered in the table when it becomes its
    /// children's corner, for the test of where G bends to find on the grid lines through
    /// corners (BasicContourOptions::bends_through_centres). In space it is there already.
    void enter_centres_as_corners(bool on) { centres_as_corners_ = on; }

    /// Samples tree's cells; G by g, bounds on it by bounds (optional); distance_slack δ as
    /// above (unset: no stand-ins from donors), widened by rounding, the allowance for rounding
    /// in G and in the bounds; η, below which a stand-in's lower bound does not give a sign; γ
    /// tests cells above level limit. The tree must outlive the sampler.
    TreeSampler(const Tree& tree, FunctionRef g, std::optional<BoundsRef> bounds,
                std::optional<double> distance_slack, double rounding, double eta, int limit);

    /// Samples the given cells (the root, or children of sampled cells), in order: new points
    /// whose sign neither their parent's samples nor the bounds (one batch) give are evaluated,
    /// in one batch.
    void sample(std::span<const std::uint32_t> cells);
    /// Before the cells are tested against γ: resolves the stand-ins on which a test would rest,
    /// so each test sees what exact values would decide. The parents' stand-ins among them are
    /// offered to the bounds first (one batch); those still below the threshold are evaluated
    /// (one batch).
    void settle_tests(std::span<const std::uint32_t> cells, double gamma);

    /// Whether cell c has been sampled: sample() needs every cell's parent sampled first.
    bool has_samples(std::uint32_t c) const {
        return c < cell_samples_.size() && cell_samples_[c][0] != no_sample;
    }
    /// The least |G| (or stand-in) at the samples of cell c.
    double min_abs(std::uint32_t c) const { return cell_min_[c]; }
    /// The level below which γ tests cells.
    int limit() const { return limit_; }

    /// What a cell's samples say of G bending within it.
    enum class Bend { no, yes, unsure };
    /// Whether G bends within cell c (which samples its centre): on a diagonal through the centre,
    /// or on a grid line through a corner with the corners an edge away on both sides, the ends
    /// of one sign, the middle of theirs (or within η of zero) and nearer zero than the ends'
    /// mean by more than thin_dip of half the span. A distance is linear along a segment on one
    /// side of a line or plane and bends by about h²/(2R) near a curve or sheet of radius R: a
    /// dip this large means the zero set turns within the cell or its other side is there too. Only
    /// cells the zero set may meet are tested (the centre's |G| at most the half-diagonal). From
    /// the samples' bounds: unsure when stand-ins leave it open, and then the stand-ins that would
    /// settle it are appended to `wanted`.
    Bend bends(std::uint32_t c, std::vector<std::uint32_t>& wanted) const;
    /// Makes G exact at the given sample ids (from bends), in one batch, and updates the least
    /// |G| of the given cells.
    void make_exact(std::vector<std::uint32_t> ids, std::span<const std::uint32_t> cells);
    /// Tree points with a stand-in rather than G.
    std::size_t settled() const;
    /// Whether G (or its stand-ins, which carry its sign) takes both signs at c's samples.
    bool changes_sign(std::uint32_t c) const {
        bool negative = false, positive = false;
        for (const std::uint32_t id : samples_of(c))
            (samples_[id].value > 0.0 ? positive : negative) = true;
        return negative && positive;
    }
    /// Evaluations of the bounds so far.
    std::size_t bound_evals() const { return bound_evals_; }

protected:
    static constexpr double infinity = std::numeric_limits<double>::infinity();
    /// No sample yet: the centre of a cell at the depth limit in the plane, before it is made.
    static constexpr std::uint32_t no_sample = 0xffffffffu;
    using CellSamples = std::array<std::uint32_t, cell_points>;

    /// A cell's sample points, as keys and grid points: corners, then the centre when the cell
    /// samples it (or always, with with_centre).
    struct Keys {
        std::array<std::uint64_t, cell_points> k;
        std::array<typename SampleGrid<dim>::Coords, cell_points> at;
        std::size_t n;
    };
    Keys sample_keys(std::uint32_t c, bool with_centre = false) const;
    /// The sample ids of cell c: its corners, then its centre when it has one.
    std::span<const std::uint32_t> samples_of(std::uint32_t c) const {
        const bool centre = centres_at_depth_limit || tree_.cell(c).level < tree_.max_depth();
        return std::span(cell_samples_[c]).first(centre ? cell_points : cell_points - 1);
    }
    /// The bounds that the known samples among ids (the donors) give on G at x: a stand-in when
    /// they give its sign. None without a distance slack.
    std::optional<Sample> from_donors(Point x, std::span<const std::uint32_t> ids) const;
    /// Whether from_donors(x, ids) gives a stand-in: whether one of the donors' bounds gives G's
    /// sign at x (tried in the order given, to the first that does).
    bool signed_by_donors(Point x, std::span<const std::uint32_t> ids) const;
    /// The bounds at the samples ids (one batch; none without bounds), widened by the rounding
    /// allowance, tighten their stand-ins, or make stand-ins of the points pending for G whose
    /// sign they give. Returns the samples still pending.
    std::vector<std::uint32_t> apply_bounds(std::vector<std::uint32_t> ids);
    /// G at the samples ids, in one batch.
    void evaluate(std::span<const std::uint32_t> ids);
    /// Recomputes the least |G| of cell c.
    void update_min(std::uint32_t c);

    const Tree& tree_;
    SampleGrid<dim> grid_;
    /// Every sample point: where it is, G there or a stand-in.
    std::vector<Point> points_;
    std::vector<Sample> samples_;
    /// Sample ids by key: the corners of every cell (and centres, centres_in_table).
    KeyMap<std::uint32_t> index_;
    /// Per cell, the ids of its corners (in sample_keys() order) and centre.
    std::vector<CellSamples> cell_samples_;
    bool centres_as_corners_ = false;  ///< (enter_centres_as_corners)

private:
    /// The id of sample j of keys, and whether it is new (then pending for G).
    std::pair<std::uint32_t, bool> add_point(const Keys& keys, std::size_t j);
    /// Sample j of child c, as add_point(keys, j) would give it, with no lookup where the parent
    /// has it; the centre is new, and only its children's corners, through their parent's
    /// samples, meet it again.
    std::pair<std::uint32_t, bool> child_point(std::uint32_t c, const Keys& keys, std::size_t j);
    /// Appends sample j of keys, pending for G; returns its id.
    std::uint32_t add_pending(const Keys& keys, std::size_t j);
    /// Calls f(id, sample) once for each stand-in that the test of a touched cell needs: one
    /// whose lower bound is below the cell's threshold, in a cell where no sample's upper bound
    /// is below it.
    template <class F>
    void for_needed_stand_ins(std::span<const std::uint32_t> touched, double gamma, F f);
    /// A lower bound of |G| gives G's sign, and a stand-in, when it exceeds η (so that the point
    /// is never a perturbation candidate).
    bool certain(double lower) const { return lower > eta_; }
    /// How far a donor's bound reaches to x: |x − y| + δ for the donor at y.
    double reach(Point x, std::uint32_t id) const;
    std::vector<Point> points_of(std::span<const std::uint32_t> ids) const;

    /// Samples the arrays have room for before they first grow.
    static constexpr std::size_t reserved_samples = std::size_t{1} << 16;

    FunctionRef g_;
    std::optional<BoundsRef> bounds_;
    std::size_t bound_evals_ = 0;
    std::optional<double> slack_;
    double rounding_;
    double eta_;
    int limit_;
    std::vector<double> cell_min_;
};

/// Builds the tree down to sampler.limit(), splitting every cell whose edge exceeds min|G|/γ, γ
/// doubled until the tree is 2:1 balanced (after max_gamma_doublings, balanced by splitting);
/// every cell is sampled. The split criterion is monotone in γ, so the tree for 2γ refines the
/// tree for γ: each doubling offers the leaves to it again. Returns γ. The tree holds only its
/// root, which the sampler has not sampled.
template <int dim>
double build_tree(Orthtree<dim>& tree, TreeSampler<dim>& sampler, double gamma);

/// What split_thin did.
struct ThinSplit {
    std::size_t cells = 0;        ///< cells split beyond K
    bool budget_reached = false;  ///< some cells that bend were left whole (thin_cell_budget)
};

/// Thin cells split at most this many times the cells of the tree at depth K: a G that bends
/// almost everywhere (a coarse step of a curvature law, or a law extended from the nearest
/// point of a polygon, whose W jumps at the corners' normals) costs at most a few times a contour
/// at K.
inline constexpr std::size_t thin_cell_budget = 2;

/// Splits the leaves at level sampler.limit() (K) near the zero set (min|G| below γ times their
/// edge) where G bends within them (TreeSampler::bends), and their children where it still does,
/// down to the tree's depth limit, level by level in cell order, until thin_cell_budget times the
/// tree's cells have split; then balances the tree again, sampling the cells balancing makes.
/// Thin parts, near contacts, sharp corners and tight turns of the zero set so get cells fine
/// enough for the linear contour to have both their sides.
template <int dim>
ThinSplit split_thin(Orthtree<dim>& tree, TreeSampler<dim>& sampler, double gamma);

/// The centre of the first of the tree's deepest leaves: where its finest cells are.
template <int dim>
PointOf<dim> deepest_place(const Orthtree<dim>& tree) {
    for (std::size_t c = 0; c < tree.size(); ++c)
        if (tree.cell(c).level == tree.depth()) return tree.box(c).center();
    return tree.root_box().center();
}

/// The levels thin cells may take beyond depth K: thin_depth, short of level `deepest` and of
/// the finest cells that doubles resolve in domain.
template <int dim>
int thin_levels(const RegionOf<dim>& domain, int depth, int thin_depth, int deepest) {
    const int finest = std::min(deepest, Orthtree<dim>::max_resolvable_depth(domain));
    return std::max(0, std::min(thin_depth, finest - depth));
}

}  // namespace slc::contouring
