/// @file
/// One semi-Lagrangian time step of a surface (paper §1.2 with d = 3, DESIGN §8): the same CIR
/// predictor and trapezoidal corrector as the step of curves (step.hpp), each contour a
/// contour_surface() of exact signed distances to the surface at time t, which the octree
/// distance tree answers. A flow field needs no predictor (G(x) = F(x*), x* the foot of the
/// characteristic by the fourth-order Runge–Kutta rule); a normal law is evaluated off the surface
/// with the distance field's normal (Extension::direct); every other law is extended from the
/// vertices to the nearest point (Extension::nearest_point).
#pragma once

#include <cmath>
#include <optional>

#include "slc/contour/surface_contour.hpp"
#include "slc/core/box3.hpp"
#include "slc/evolve/step.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// The parameters of a surface step (paper Table 4).
struct SurfaceStepOptions {
    SurfaceContourOptions contour;  ///< K, P, ε, η (resolved_eta) of both contours
    int tree_depth = 0;  ///< L, the distance trees' depth; 0: SurfaceDistanceTree::default_depth
    /// How W is extended off the surface: direct or nearest_point (Whitney is for curves only);
    /// unset: resolved_extension().
    std::optional<Extension> extension = std::nullopt;
    /// σ of the curvature's smoothing (SurfaceGeometryOptions::smoothing); unset: √k, the width
    /// an explicit step of mean curvature flow needs to stay stable, as for curves.
    std::optional<double> smoothing = std::nullopt;
    /// Read S(t) as curved patches through its vertices when G is evaluated: F less the height
    /// of the quadric patch that the vertex normals give each triangle (flat at corners and
    /// sharp edges). The triangles of a surface inscribed in a smooth one cut inside its convex
    /// parts by up to h²|C|/12, and each step's new vertices land on them: a loss that adds up
    /// over the steps, which the patches remove to O(h³), as arcs do for curves.
    bool patches = true;
    /// For a law that keeps the volume (VelocityLaw::preserves_area): after the step, move every
    /// vertex of S(t + k) along its normal by δ = (V(t) − V(t + k))/A, each by at most a quarter
    /// of its shortest edge, eight times at most (to rounding); a vertex stays where it is
    /// once a shift makes the surface meet itself at one of its triangles. Unset: on for such
    /// laws.
    std::optional<bool> volume_correction = std::nullopt;

    /// The extension as given, or the law itself (direct) for flow fields and normal laws and
    /// the nearest-point extension for every other law.
    Extension resolved_extension(const SurfaceVelocityLaw& law) const;
    /// η as given, or 10⁻¹⁰ (not contour_surface's ε/100): the next step differentiates these
    /// vertices (normals, curvature), and ε/100 saves a step about a tenth of its evaluations of
    /// G but no measurable time, which goes mostly to the law and the geometry
    /// (docs/algorithms/evolve.md).
    double resolved_eta() const { return contour.eta.value_or(SurfaceContourOptions::default_eta); }
    /// σ as given, or √k.
    double resolved_smoothing(double k) const { return smoothing.value_or(std::sqrt(k)); }
    /// volume_correction as given, or by default on for laws that keep the volume.
    bool resolved_volume_correction(const SurfaceVelocityLaw& law) const {
        return volume_correction.value_or(law.preserves_area());
    }
};

/// What a surface step cost.
struct SurfaceStepStats {
    SurfaceContourStats predictor;  ///< the contour of G̃; empty for a flow field
    SurfaceContourStats corrector;  ///< the contour of G
    /// The volume given back by SurfaceStepOptions::volume_correction (0 when none was applied).
    double volume_correction = 0.0;
    /// Evaluations of G̃ and G together.
    std::size_t g_evals() const { return predictor.g_evals + corrector.g_evals; }
};

/// The surface after one step and its cost.
struct SurfaceStepResult {
    Surface surface;         ///< S(t + k); empty when everything vanished
    SurfaceStepStats stats;  ///< both contours' statistics
};

/// The volume a valid surface encloses as a step of a flow field or a normal law reads it: its
/// triangles', plus the bulges of its curved patches (SurfaceStepOptions::patches) over them.
double step_volume(const Surface& surface, const SurfaceStepOptions& options);

/// Advances a valid surface inside domain (a cube) from t to t + k under law. Components may
/// vanish; an empty result means nothing is left. Deterministic: the same for any thread count.
/// Throws InvalidInput for k ≤ 0, an empty surface, the Whitney extension, or a direct extension
/// of a law that is neither a flow field nor a normal law; LeftDomain when a contour reaches the
/// domain's boundary; NumericalFailure (from contouring or the law) when a velocity is not
/// finite.
SurfaceStepResult advance(const Surface& surface, double t, double k, const SurfaceVelocityLaw& law,
                          const Box3& domain, const SurfaceStepOptions& options);

}  // namespace slc
