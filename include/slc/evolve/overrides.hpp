/// @file
/// What a user sets of a run, over a problem's or a law's defaults (DESIGN §4): the settings that
/// `slc run`'s flags and Python's keywords carry, their ranges, and one function per dimension
/// that applies them. The tool and the Python package both call these, so that their defaults,
/// ranges and messages cannot disagree with each other or with the library.
#pragma once

#include <optional>
#include <string>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/surface_run.hpp"
#include "slc/tree/tetrahedralization.hpp"

namespace slc {

struct SurfaceProblem;

/// A closed range of an integer setting.
struct IntRange {
    int lo;  ///< least value allowed
    int hi;  ///< largest value allowed
};

/// The ranges of the integer settings, for the tool's checks and the library's.
namespace setting_range {
inline constexpr IntRange steps{1, 100'000'000};  ///< N
inline constexpr IntRange curve_depth{1, 24};     ///< K of curves (memory: 4^K cells at worst)
/// K of surfaces: as deep as tetrahedralization keys allow.
inline constexpr IntRange surface_depth{1, max_tetrahedralized_depth};
inline constexpr IntRange refine{0, 64};      ///< P, or until_converged
inline constexpr IntRange thin_depth{0, 8};   ///< levels beyond K for thin cells
inline constexpr IntRange tree_depth{1, 30};  ///< L
inline constexpr IntRange mesh{8, 1 << 22};   ///< M (curves)
inline constexpr IntRange eno_order{1, 5};    ///< E (curves)
inline constexpr IntRange smoothing{0, 64};   ///< S (curves)
/// K of the given dimension (2: curves, 3: surfaces).
constexpr IntRange depth(int dim) { return dim == 2 ? curve_depth : surface_depth; }
}  // namespace setting_range

/// The levels beyond K that a user's own shape's contours may split cells where the zero set is
/// not resolved at K (thin parts, near contacts, corners): cells down to 1/64 of a K-level cell
/// for curves, 1/4 for surfaces, whose thin cells cost about 4 times more a level (a wall a
/// third of a cell thick takes two). Named problems keep the paper's uniform K (theirs is 0,
/// Enright's 2).
constexpr int default_thin_depth(int dim) { return dim == 2 ? 6 : 2; }

/// K of a user's shape in its default domain (1.5 times the shape's box): cells 1/32 of it.
inline constexpr int default_depth = 5;

/// K for a user's shape in a domain `domain_width` wide whose default domain (1.5 times the
/// shape's box) is `default_width` wide: default_depth, and one level more for each doubling of the
/// domain beyond the default, so that the finest cell stays the default's (--domain 150 around a
/// unit circle takes K = 12, cells of 0.073, where K = 5 made them 9.4); within K's range for dim.
int depth_for_domain(int dim, double domain_width, double default_width);

/// ε that K sets when ε is not given, in both dimensions the rule a user's own shape defaults to
/// (ℓ its length scale, 1 for a named problem): 10^−K ℓ for curves, as the paper's runs
/// N/S/K/P/ε (not below 1e−13 ℓ, as fine as root finding places a vertex); 10^−3 · 4^(5−K) ℓ
/// for surfaces, the default 10^−3 ℓ at K = 5 scaled as h², since a surface refined to ε takes
/// about 1/ε triangles where a curve takes 1/√ε segments. dim is 2 or 3.
double eps_for_depth(int dim, int depth, double length_scale);
/// The least ε that eps_for_depth gives curves, times ℓ.
inline constexpr double min_curve_eps = 1e-13;

/// ε and η of one contour.
struct ContourTolerances {
    double eps = 0.0;  ///< ε
    double eta = 0.0;  ///< η
};

/// ε and η for contouring a user's shape of length scale ℓ (1 for a built-in function) at depth
/// K with P passes, each as given or, unset, by the rule its runs follow, so that a shape scaled
/// by any factor contours alike: ε = eps_for_depth(dim, K, ℓ); η = 1e−10 ℓ, for curves lowered
/// to ε/10 when ε is below it, for surfaces refined (P ≠ 0) raised to ε/100 (the rule of
/// SurfaceContourOptions::resolved_eta, scaled).
ContourTolerances contour_tolerances(int dim, int depth, int refine_passes, double length_scale,
                                     std::optional<double> eps, std::optional<double> eta);

/// The settings a user gave of a run; unset ones keep the problem's or the law's defaults. Names
/// are those of the Python keywords; `name_of` below gives the tool's flags.
struct RunOverrides {
    std::optional<int> steps = std::nullopt;   ///< N
    std::optional<int> depth = std::nullopt;   ///< K; without eps, ε follows it (eps_for_depth)
    std::optional<int> refine = std::nullopt;  ///< P, or ContourOptions::until_converged
    std::optional<double> eps = std::nullopt;  ///< ε
    std::optional<double> eta =
        std::nullopt;  ///< η; for curves, unset: lowered to ε/10 when ε is below it
    std::optional<int> tree_depth = std::nullopt;  ///< L
    // Curves only.
    std::optional<double> rho = std::nullopt;           ///< ρ, the pruning ratio in [0, 1)
    std::optional<int> mesh = std::nullopt;             ///< M; unset: 2^(K+1)
    std::optional<int> eno_order = std::nullopt;        ///< E
    std::optional<int> smoothing = std::nullopt;        ///< S
    std::optional<Extension> extension = std::nullopt;  ///< how W leaves the curve
    std::optional<bool> arcs = std::nullopt;            ///< StepOptions::arcs
    std::optional<double> arc_width = std::nullopt;     ///< σ of the arclength module
    /// Levels beyond K for cells where the zero set is not resolved (ContourOptions::thin_depth,
    /// SurfaceContourOptions::thin_depth); unset: the problem's, or default_thin_depth for a
    /// user's shape.
    std::optional<int> thin_depth = std::nullopt;
    /// RunOptions::stop_components, SurfaceRunOptions::stop_components.
    std::optional<std::size_t> until_components = std::nullopt;
    // Surfaces only.
    std::optional<double> volume_drift = std::nullopt;  ///< SurfaceRunOptions::volume_drift
    std::optional<bool> guards = std::nullopt;  ///< RunOptions::guards, SurfaceRunOptions::guards
    /// Curves: StepOptions::area_correction; surfaces: SurfaceStepOptions::volume_correction.
    std::optional<bool> area_correction = std::nullopt;
    /// The frames the front end writes (`--frames`, `frames=`): a user's run whose N is not
    /// given takes the least multiple of them at or above its default N, so that they fall at
    /// evenly spaced times (run_options, surface_run_options); a named problem keeps its N and
    /// writes at most a frame a step.
    std::optional<int> frames = std::nullopt;
};

/// How a front end names the settings in its messages.
enum class SettingNames {
    python,  ///< the keywords: depth, eps, thin_depth
    tool,    ///< the flags: -K/--depth, --eps, --thin-depth
};

/// The run options of curves: overrides over `defaults` (problem_run_options of a problem, or
/// default_run_options of a user's curves), ℓ = length_scale. K without ε sets ε by
/// eps_for_depth and M by default_mesh_size. Throws InvalidInput naming the setting (in `names`)
/// for a value out of range, ε below η, or a setting of surfaces.
RunOptions apply_overrides(const RunOverrides& overrides, RunOptions defaults, double length_scale,
                           SettingNames names = SettingNames::python);

/// The run options of surfaces, the same way: overrides over `defaults`
/// (named_surface_run_options or default_surface_run_options). Throws InvalidInput as above,
/// and for a setting of curves.
SurfaceRunOptions apply_overrides(const RunOverrides& overrides, SurfaceRunOptions defaults,
                                  double length_scale, SettingNames names = SettingNames::python);

/// The options a named problem of surfaces runs with: its N, K and ε, refinement until
/// converged, its thin depth, and a fixed domain.
SurfaceRunOptions named_surface_run_options(const SurfaceProblem& problem);

/// A problem of curves' run options: overrides over problem_run_options(problem), ℓ its length
/// scale, and for a user's curves a whole number of steps a frame (RunOverrides::frames). Throws as
/// apply_overrides.
RunOptions run_options(const Problem& problem, const RunOverrides& overrides,
                       SettingNames names = SettingNames::python);

/// A problem of surfaces' run options: overrides over named_surface_run_options (a named
/// problem, ℓ = 1) or over default_surface_run_options from t_start (a user's surface, ℓ its
/// length_scale; a whole number of steps a frame, RunOverrides::frames). Throws as apply_overrides
/// and default_surface_run_options.
SurfaceRunOptions surface_run_options(const SurfaceProblem& problem, bool named, double t_start,
                                      const RunOverrides& overrides,
                                      SettingNames names = SettingNames::python);

/// True when overrides set any of K, P, ε, η or the thin depth: a named problem's surface is then
/// contoured again with them (a run at K = 7 starts from the contour at K = 7).
bool sets_contour(const RunOverrides& overrides);

}  // namespace slc
