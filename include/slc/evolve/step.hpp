/// @file
/// One semi-Lagrangian time step t → t + k (paper §1.2, §4.3; DESIGN §1): the CIR predictor
/// G̃(x) = F(x − k W(x, t); Γ(t)) contoured to Γ̃, then the trapezoidal corrector
/// G(x) = F(x − k W̄(x); Γ(t)), W̄(x) = ½ W(x − k W(x, t), t) + ½ W̃(x, t + k), contoured to Γ(t + k).
/// A flow field sampled directly (Extension::direct) needs no predictor: G(x) = F(x*; Γ(t)) with x*
/// the foot of the characteristic through x traced back by the fourth-order Runge–Kutta rule, in
/// as many substeps as bring the feet of Γ(t)'s vertices within ε/10.
/// Every G value is an exact signed distance, so max |G| never grows: explicit, unconditionally
/// stable in the maximum norm, second order in time.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "slc/contour/contour.hpp"
#include "slc/core/box.hpp"
#include "slc/core/names.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry_modules/arclength.hpp"
#include "slc/geometry_modules/embedded.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// How the vertex velocities become the advection velocity W off the curve (§1.3).
enum class Extension {
    nearest_point,  ///< W(x) = u at the nearest point of Γ (the paper's choice)
    whitney,        ///< the continuous piecewise-linear Whitney extension on the distance tree
    /// The law itself evaluated off the curve, for flow fields and normal laws only. A flow field
    /// is sampled along each characteristic, its foot found by the classical Runge–Kutta rule in
    /// as many substeps as bring it within ε/10: one contour per step. A normal law V(t, x, N) is
    /// evaluated at x with the normal of the distance field there, N = sign F(x) (x − y)/|x − y|, y
    /// the nearest point of Γ: the exact offset of the polygon under a constant speed, so a growing
    /// corner rounds off and a shrinking one stays sharp, as in the exact (viscosity) solution.
    direct,
};

/// The extensions' names, as --extension, Python and summary.json spell them.
inline constexpr Named<Extension> extension_names[] = {{"nearest", Extension::nearest_point},
                                                       {"whitney", Extension::whitney},
                                                       {"direct", Extension::direct}};
/// The extension's name.
inline const char* to_string(Extension e) { return name_of<Extension>(extension_names, e); }

/// The parameters of a step (paper Table 4).
struct StepOptions {
    ContourOptions contour;  ///< K, P, ε, η, ρ of both contours
    int tree_depth = 0;      ///< L, the distance trees' depth; 0 means the default below
    /// How W is extended off Γ; unset: resolved_extension().
    std::optional<Extension> extension = std::nullopt;
    EmbeddedOptions embedded;  ///< M, E, S for laws that use the embedded geometry module
    /// σ of the arclength geometry module; unset: √k, above the 0.76 √k that an explicit step
    /// of curvature flow needs to be stable (docs/algorithms/geometry.md).
    std::optional<double> arc_width;
    /// Read Γ(t) as arcs through its vertices instead of its chords when G is evaluated:
    /// F(y) + ½ c² t (1 − t) C(t) at a point y whose nearest point is at parameter t of a segment
    /// of length c, C the signed curvature (−1/R on a counterclockwise circle) of the circles
    /// through each end and its two neighbours, interpolated linearly in t; C = 0 at a corner,
    /// where the curve turns by more than arc_corner, and under a rigid motion (which keeps any
    /// shape) also where a segment is longer than arc_longest finest cells: there only the
    /// contours' chords (at most a cell's diagonal) need the arcs, and a user's coarser polygon
    /// is moved as the polygon it is, its sides straight. The chords of a polygon inscribed in a
    /// smooth curve cut inside its convex parts by up to c²|C|/8, and each step's new vertices
    /// land on them: a loss that adds up over the steps. The arcs remove it to O(c³); corners stay
    /// sharp (docs/algorithms/evolve.md). Unset: resolved_arcs().
    std::optional<bool> arcs = std::nullopt;
    /// For a law that keeps area (VelocityLaw::preserves_area): after the step, give Γ(t + k)
    /// back the area of Γ(t) by restore_area. Unset: on for such laws.
    std::optional<bool> area_correction = std::nullopt;
    /// Turning angle at a vertex (radians) above which arcs treats it as a corner.
    static constexpr double arc_corner = corner_turn;
    /// Length of a segment, in finest cells of the contours (finest_cell), above which arcs treats
    /// its ends as corners under a rigid motion.
    static constexpr double arc_longest = 2.0;

    /// σ of the arclength module for a step of size k: arc_width as given, or √k.
    double resolved_arc_width(double k) const { return arc_width.value_or(std::sqrt(k)); }
    /// The extension as given, or by default the law itself (direct) for flow fields and normal
    /// laws, and the nearest-point extension for every other law.
    Extension resolved_extension(const VelocityLaw& law) const;
    /// arcs as given, or by default on for laws whose curvature comes from the arclength module
    /// (curvature flow: the chords' loss would otherwise add up over the steps), for laws that fit
    /// smooth curves themselves (GeometryNeeds::smooth), and for laws evaluated directly (normal
    /// laws and flow fields: an offset of a smooth curve then converges at second order in time
    /// instead of losing a chord's sagitta every step).
    bool resolved_arcs(const VelocityLaw& law) const;
    /// area_correction as given, or by default on for laws that keep the area.
    bool resolved_area_correction(const VelocityLaw& law) const {
        return area_correction.value_or(law.preserves_area());
    }

    /// L as given, or by default K + ⌊min(P, 4)/2⌋ (K + P with the Whitney extension, whose
    /// accuracy depends on L); refinement until converged counts as P = 4. Only the Whitney
    /// extension's results depend on L: every other use of the trees is an exact distance.
    int resolved_tree_depth() const;
};

/// What a step cost.
struct StepStats {
    ContourStats predictor;  ///< the contour of G̃ (CIR predictor); empty for a direct step
    ContourStats corrector;  ///< the contour of G (trapezoidal corrector)
    /// The area given back by StepOptions::area_correction (0 when none was applied).
    double area_correction = 0.0;
    /// Evaluations of G̃ and G together, and the vertices both contours produced.
    std::size_t g_evals() const { return predictor.g_evals + corrector.g_evals; }
    /// @copybrief g_evals
    std::size_t vertices() const { return predictor.vertices + corrector.vertices; }
};

/// The curves after one step and its cost.
struct StepResult {
    Interface curves;  ///< Γ(t + k); empty when everything vanished
    StepStats stats;   ///< both contours' statistics
};

/// Curves moved to a given area, and the area that added.
struct AreaRestored {
    Interface curves;    ///< the moved curves
    double added = 0.0;  ///< their area less the area of the curves given
};

/// The curves moved along their vertex normals (the bisectors of the segments' normals) until
/// they enclose `target`: shifts of δ = (target − A)/L, each vertex by at most a quarter of its
/// shorter segment, each leaving O(δ²) of the difference, eight at most (to rounding). A vertex
/// stays where it is once a shift makes the curves cross at one of its segments (found by
/// find_crossing, O(N log N)), as a zigzag of segments far shorter than the shift would. The
/// curves as given when no vertex can move. StepOptions::area_correction after every step.
AreaRestored restore_area(const Interface& curves, double target);

/// The same for each region of the curves on its own (region[c] of curve c, curve_regions):
/// region r moved to enclose target[r], its shift δ_r = (target[r] − A_r)/L_r. After a step of a
/// law that keeps each region's area (Invariants::keeps_region_areas).
AreaRestored restore_region_areas(const Interface& curves, std::span<const std::size_t> region,
                                  std::span<const double> target);

/// The edge of the finest cell of contours at depth `contour.depth` in domain (the same in the
/// domain doubled, K a level deeper each time).
double finest_cell(const Box& domain, const ContourOptions& contour);

/// The area enclosed by curves as a step in domain reads them: the polygon's, plus the bulges of
/// its arcs when the step reads it as arcs (StepOptions::resolved_arcs).
double step_area(const Interface& curves, const VelocityLaw& law, const StepOptions& options,
                 const Box& domain);

/// The length of curves as a step in domain reads them: the polygon's, or its arcs' when the step
/// reads it as arcs.
double step_length(const Interface& curves, const VelocityLaw& law, const StepOptions& options,
                   const Box& domain);
/// step_area and step_length at once, the arcs' curvatures computed once.
std::pair<double, double> step_area_and_length(const Interface& curves, const VelocityLaw& law,
                                               const StepOptions& options, const Box& domain);

/// Advances curves (inside domain, a square) from t to t + k under law. Components may vanish;
/// an empty result means nothing is left. Throws InvalidInput for k ≤ 0 or a direct extension of
/// a law that is not a flow field; NumericalFailure (from contouring or the law) when the contour
/// reaches the domain boundary or a velocity is not finite.
StepResult advance(const Interface& curves, double t, double k, const VelocityLaw& law,
                   const Box& domain, const StepOptions& options);

}  // namespace slc
