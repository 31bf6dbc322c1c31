/// @file
/// The named problems of moving surfaces (`slc run --problem NAME`, DESIGN §8), and what a run of
/// a user's surface (`slc run --initial S.obj`) takes by default: its domain, its length scale and
/// its run options. The built-in laws of surfaces by name are in velocity/factory.hpp.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/evolve/surface_run.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/velocity/factory.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// The first row of a problem's convergence study (surface_study): N, K and ε of refinement.
struct SurfaceStudyPlan {
    int steps = 0;     ///< N
    int depth = 0;     ///< K
    double eps = 0.0;  ///< ε
};

/// A named problem: the initial surface, its law, domain, time and default parameters, and the
/// exact solution where one is known.
struct SurfaceProblem {
    std::string name;                         ///< as in --problem NAME
    std::string description;                  ///< one line
    Surface initial;                          ///< the surface at t = 0
    std::unique_ptr<SurfaceVelocityLaw> law;  ///< its law
    Box3 domain;                              ///< a cube
    double t_end = 1.0;                       ///< the final time
    int steps = 20;                           ///< N
    int depth = 5;                            ///< K
    double eps = 1e-4;                        ///< ε of refinement (until converged)
    int thin_depth = 0;                       ///< SurfaceContourOptions::thin_depth of its steps
    /// The exact signed distance (or a function with the same zero set) at time t, NaN where the
    /// exact surface is not known at t; empty when it is never known.
    std::function<double(double t, Vec3 x)> exact;
    /// The direction its pictures look from: degrees about the z axis from the +x axis, and
    /// above the xy plane (SurfaceView).
    double azimuth = 35.0;
    double elevation = 25.0;  ///< (see azimuth)
    /// The implicit function whose contour is the initial surface (negative inside), empty for
    /// a surface given by its triangles (box-normal); 1-Lipschitz, so initial_surface()
    /// contours it with a distance slack of 0.
    std::function<double(Vec3)> initial_function;
    /// Its convergence study's first row; unset for a problem without one.
    std::optional<SurfaceStudyPlan> study;
};

/// The problems' names: sphere-rotation, enright, zalesak-sphere, sphere-curvature,
/// merging-spheres, box-normal, peanut-volume.
const std::vector<std::string>& surface_problem_names();
/// The one-line summary of a problem, empty for an unknown name.
std::string surface_problem_summary(const std::string& name);
/// True for one of surface_problem_names().
bool is_surface_problem(const std::string& name);

/// The problem `name`; params: `speed` of box-normal (1: growing edges round off; −1: shrinking
/// edges stay sharp). Throws InvalidInput for an unknown name or parameter.
SurfaceProblem make_surface_problem(const std::string& name, const VelocityParams& params = {});

/// The problem's initial surface contoured with the given options (a run's K, P and ε) when it
/// comes from an implicit function; a surface given by its triangles as it is. Throws as
/// contour_surface() does.
Surface initial_surface(const SurfaceProblem& problem, const SurfaceContourOptions& options);

/// The default domain of a user's surface whose bounding box is `bounds`: the cube centred on it
/// with 1.5 times its largest half-side, as default_domain of curves. Throws InvalidInput when
/// the surface spans less than tolerance::min_domain_width.
Box3 default_domain(const Box3& bounds);

/// ℓ, the largest half-side of the surface's bounding box: the length a user's surface's
/// defaults scale with. Precondition: surface is not empty.
double length_scale(const Surface& surface);

/// The run options for a user's surface (valid, not empty) from t_start to t_end under law,
/// lengths relative to ℓ = length_scale(surface): N = 20 steps, K = 5 (the finest cell 1/32 of the
/// domain), refinement until converged with ε = 1e−3 ℓ (eps_for_depth, the rule -K follows)
/// (triangles grow as 1/ε: a sphere takes about 20,000), η = 1e−10 ℓ; the law's own extension, and
/// the curvature smoothed over √k. Throws InvalidInput for an empty surface or t_end not after
/// t_start.
SurfaceRunOptions default_surface_run_options(const Surface& surface, const SurfaceVelocityLaw& law,
                                              double t_start, double t_end);

}  // namespace slc
