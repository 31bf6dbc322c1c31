// The settings for a user's own curves.
#include "slc/evolve/defaults.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/geometry_modules/arclength.hpp"
#include "user_defaults.hpp"

namespace slc {

Box default_domain(const std::vector<std::vector<Vec2>>& curves) {
    Box bounds = Box::empty();  // of the finite points: validation reports the others
    for (const auto& curve : curves) bounds = unite(bounds, bounding_box(curve));
    if (bounds.is_empty()) throw InvalidInput("no curves: the interface is empty");
    double half = 1.5 * std::max(0.5 * bounds.width(), 0.5 * bounds.height());
    if (half == 0.0) half = 1.0;  // all points at one place: validation names the curve
    if (!(2.0 * half >= tolerance::min_domain_width)) {
        throw InvalidInput(fmt::format(
            "the curves span only {:.3g}: give --domain or --box at least {:g} wide, or scale them",
            std::max(bounds.width(), bounds.height()), tolerance::min_domain_width));
    }
    return Box::square(bounds.center(), half);
}

double length_scale(const Interface& curves) {
    const Box bounds = bounding_box(curves.points());
    return 0.5 * std::max(bounds.width(), bounds.height());
}

namespace {

/// The largest |C| of the circles through each vertex and its two neighbours (circle_curvature).
double sharpest_turn(const Interface& curves) {
    double most = 0.0;
    for (std::size_t v = 0; v < curves.size(); ++v) {
        const Vec2 b = curves.point(v), u = b - curves.point(curves.prev(v)),
                   w = curves.point(curves.next(v)) - b;
        if (norm(u) * norm(w) * norm(u + w) > 0.0)
            most = std::max(most, std::abs(circle_curvature(u, w)));
    }
    return most;
}

/// A user's run takes 40 steps, or for a stiff law (VelocityLaw::stiffness) enough that each
/// step moves the sharpest turn of the start by a quarter of its rate's e-fold at most (an
/// ellipse 0.8 × 0.4 under Hele-Shaw keeps corners at its tips, 0.017 from the circle it relaxes
/// to at t = 0.5, in 40 steps; 1e−4 in 250), up to 2,000.
int default_steps(const Interface& curves, const VelocityLaw& law, double t_start, double t_end) {
    constexpr int fewest = detail::user_steps(2), most = 2000;
    const double wanted = 4.0 * (t_end - t_start) * law.stiffness(sharpest_turn(curves));
    if (!(wanted > fewest)) return fewest;
    return wanted >= most ? most : static_cast<int>(std::ceil(wanted));
}

}  // namespace

RunOptions default_run_options(const Interface& curves, const VelocityLaw& law, double t_start,
                               double t_end) {
    if (curves.empty()) throw InvalidInput("no curves: the interface is empty");
    RunOptions o = detail::user_run_options<2, RunOptions>(
        law, t_start, t_end, length_scale(curves), default_steps(curves, law, t_start, t_end));
    ContourOptions& c = o.step.contour;
    // A law known only at the vertices (the curvature laws, a law of their velocities) is
    // extended off the curve from its nearest point, whose kinks refinement to convergence would
    // chase without end, and curvature is noisier where refinement leaves the vertices unevenly
    // spaced: such laws take the paper's two passes. A law known everywhere (flow fields, normal
    // laws) is evaluated directly, where a pass splits only the segments whose midpoint misses
    // ε, so refining to convergence puts the cost where the curve needs it.
    const bool at_vertices = o.step.resolved_extension(law) != Extension::direct;
    c.refine_passes = at_vertices ? 2 : ContourOptions::until_converged;
    c.triangle_safeguard = false;
    // A normal law whose speed depends on the normal (anisotropic, a speed expression in the
    // normal) leaves G loops smaller than a cell at the corners where its Wulff shape is not
    // convex. Thin cells 6 deep resolve them as parts or holes the law forbids, at many times
    // the cost (a unit circle under the law's own speed to t = 0.5: 101 s CPU, against 7 s two
    // deep), and ended 11 of the defaults campaign's 29 anisotropic runs unstable. Two levels, as
    // for a surface: a start with a part thinner than that still takes more (check_start).
    if (detail::normal_speed_varies(law)) c.thin_depth = 2;
    o.step.embedded.mesh = default_mesh_size(c.depth);
    // A user's run holds its law's area rate to 1% of the start's area, splitting the steps
    // that would take it further (a thin ellipse's tips at 40 steps miss it by 2.4%).
    o.area_drift = 0.01;
    // And to 2% of the law's own change: a run that ends ok keeps dA/dt = -2 pi a curve.
    o.area_rate_drift = 0.02;
    // Each step within half its share of what is left of the 1%: a thin ellipse's first steps,
    // at its sharp tips, lagged by 0.15% of its area each at 40 steps, and the run ran out of
    // budget half way; at the whole share a run that ends ok spends nearly all of it.
    o.area_step_share = 0.5;
    o.check_start = true;
    return o;
}

Problem curve_problem(std::string name, const Interface& curves, const Box& domain, double t_start,
                      double t_end, const VelocityLaw& law, std::string velocity,
                      VelocityParams params) {
    const RunOptions defaults = default_run_options(curves, law, t_start, t_end);
    Problem p;
    p.name = std::move(name);
    p.initial = curves.curves();
    p.domain = domain;
    p.t_start = t_start;
    p.t_end = t_end;
    p.velocity = std::move(velocity);
    p.velocity_params = std::move(params);
    p.length_scale = length_scale(curves);
    p.named = false;
    p.flow_field = law.is_field();
    p.run = defaults;
    ContourOptions& c = p.run.step.contour;
    c.depth = depth_for_domain(2, domain.width(), default_domain(curves.curves()).width());
    c.eta = c.resolved_eta();
    return p;
}

}  // namespace slc
