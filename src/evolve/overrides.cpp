// A user's settings of a run applied over a problem's or a law's defaults, for curves and for
// surfaces, with every range check in one place.
#include "slc/evolve/overrides.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "slc/core/error.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/geometry_modules/embedded.hpp"
#include "user_defaults.hpp"

namespace slc {
namespace {

/// A setting's name as a front end spells it: Python's keyword, or the tool's flag.
struct Name {
    const char* python;
    const char* tool;
};

constexpr Name steps_name{"steps", "--steps"};
constexpr Name depth_name{"depth", "--depth"};
constexpr Name refine_name{"refine", "--refine"};
constexpr Name eps_name{"eps", "--eps"};
constexpr Name eta_name{"eta", "--eta"};
constexpr Name tree_depth_name{"tree_depth", "--tree-depth"};

/// Reads the overrides with the names of one front end and checks each value's range.
class Checker {
public:
    explicit Checker(SettingNames names) : names_(names) {}

    const char* operator()(Name n) const {
        return names_ == SettingNames::python ? n.python : n.tool;
    }

    /// v within r (or, with `converged`, ContourOptions::until_converged); InvalidInput else.
    void range(std::optional<int> v, IntRange r, Name n, const char* what = "",
               bool converged = false) const {
        if (!v || (*v >= r.lo && *v <= r.hi)) return;
        if (converged && *v == ContourOptions::until_converged) return;
        throw InvalidInput(fmt::format("{}: must be an integer from {} to {}{}{}, got {}",
                                       (*this)(n), r.lo, r.hi, converged ? " or 'converged'" : "",
                                       what, *v));
    }
    /// v positive and finite; InvalidInput else.
    void positive(std::optional<double> v, Name n) const {
        if (v && !(*v > 0.0 && std::isfinite(*v)))
            throw InvalidInput(
                fmt::format("{}: must be a positive finite number, got {}", (*this)(n), *v));
    }
    /// ε ≥ η; InvalidInput naming both else.
    void eps_not_below_eta(double eps, double eta) const {
        if (eps < eta) {
            throw InvalidInput(fmt::format("{} ({}) must not be below {} ({})", (*this)(eps_name),
                                           eps, (*this)(eta_name), eta));
        }
    }
    /// InvalidInput naming the first setting q gives that is for the other dimension than dim
    /// (2: curves, 3: surfaces).
    void only_for(const RunOverrides& q, int dim) const {
        struct OneDimension {
            bool given;
            Name name;
            int dim;  ///< the dimension it is for
        };
        const OneDimension settings[] = {
            {q.rho.has_value(), {"rho", "--rho"}, 2},
            {q.mesh.has_value(), {"mesh", "--mesh"}, 2},
            {q.eno_order.has_value(), {"eno_order", "--eno-order"}, 2},
            {q.smoothing.has_value(), {"smoothing", "-S/--smooth"}, 2},
            {q.extension.has_value(), {"extension", "--extension"}, 2},
            {q.arcs.has_value(), {"arcs", "--arcs"}, 2},
            {q.arc_width.has_value(), {"arc_width", "--arc-width"}, 2},
            {q.volume_drift.has_value(), {"volume_drift", "--volume-drift"}, 3},
        };
        const auto shapes = [](int d) { return d == 2 ? "curves" : "surfaces"; };
        for (const OneDimension& s : settings) {
            if (s.given && s.dim != dim) {
                throw InvalidInput(fmt::format("{} is for {}, not {}", (*this)(s.name),
                                               shapes(s.dim), shapes(dim)));
            }
        }
    }

private:
    SettingNames names_;
};

/// The settings both dimensions share: N, K, P, their ranges, and ε and η checked positive,
/// after checking that q sets none of the other dimension's. Returns the checker of `names`, for
/// the dimension's own settings.
template <class Options>
Checker apply_shared(const RunOverrides& q, SettingNames names, int dim, Options& o) {
    const Checker check(names);
    check.only_for(q, dim);
    check.range(q.steps, setting_range::steps, steps_name);
    check.range(q.depth, setting_range::depth(dim), depth_name,
                dim == 2 ? " for curves" : " for a surface");
    check.range(q.refine, setting_range::refine, refine_name, "", true);
    check.range(q.tree_depth, setting_range::tree_depth, tree_depth_name);
    check.range(q.thin_depth, setting_range::thin_depth, {"thin_depth", "--thin-depth"});
    check.positive(q.eps, eps_name);
    check.positive(q.eta, eta_name);
    if (q.steps) o.steps = *q.steps;
    if (q.refine) o.step.contour.refine_passes = *q.refine;
    if (q.tree_depth) o.step.tree_depth = *q.tree_depth;
    if (q.thin_depth) o.step.contour.thin_depth = *q.thin_depth;
    if (q.guards) o.guards = *q.guards;
    if (q.until_components) o.stop_components = *q.until_components;
    return check;
}

}  // namespace

double eps_for_depth(int dim, int depth, double length_scale) {
    if (dim == 2) return std::max(std::pow(10.0, -depth), min_curve_eps) * length_scale;
    return 1e-3 * std::pow(4.0, 5 - depth) * length_scale;
}

ContourTolerances contour_tolerances(int dim, int depth, int refine_passes, double length_scale,
                                     std::optional<double> eps, std::optional<double> eta) {
    ContourTolerances t;
    t.eps = eps.value_or(eps_for_depth(dim, depth, length_scale));
    const double linear = SurfaceContourOptions::default_eta * length_scale;
    if (eta)
        t.eta = *eta;
    else if (dim == 2)
        t.eta = std::min(linear, 0.1 * t.eps);
    else
        t.eta = refine_passes == 0 ? linear : std::max(linear, 0.01 * t.eps);
    return t;
}

RunOptions apply_overrides(const RunOverrides& q, RunOptions r, double length_scale,
                           SettingNames names) {
    const Checker check = apply_shared(q, names, 2, r);
    check.range(q.mesh, setting_range::mesh, {"mesh", "--mesh"});
    check.range(q.eno_order, setting_range::eno_order, {"eno_order", "--eno-order"});
    check.range(q.smoothing, setting_range::smoothing, {"smoothing", "--smooth"});
    if (q.rho && !(*q.rho >= 0.0 && *q.rho < 1.0))
        throw InvalidInput(
            fmt::format("{}: must be in [0, 1), got {}", check({"rho", "--rho"}), *q.rho));
    if (q.arc_width && !(*q.arc_width >= 0.0 && std::isfinite(*q.arc_width))) {
        throw InvalidInput(fmt::format("{}: must be a non-negative finite number, got {}",
                                       check({"arc_width", "--arc-width"}), *q.arc_width));
    }
    ContourOptions& c = r.step.contour;
    if (q.depth) {
        c.depth = *q.depth;
        c.eps = eps_for_depth(2, c.depth, length_scale);
        r.step.embedded.mesh = default_mesh_size(c.depth);
    }
    if (q.eps) c.eps = *q.eps;
    // An η left unset is lowered to ε/10 when ε is below it, so that any K runs with the default.
    c.eta = q.eta ? *q.eta : std::min(c.resolved_eta(), 0.1 * *c.eps);
    check.eps_not_below_eta(*c.eps, *c.eta);
    if (q.rho) c.rho = *q.rho;
    if (q.mesh) r.step.embedded.mesh = *q.mesh;
    if (q.eno_order) r.step.embedded.eno_order = *q.eno_order;
    if (q.smoothing) r.step.embedded.smoothing = *q.smoothing;
    if (q.extension) r.step.extension = *q.extension;
    if (q.arcs) r.step.arcs = q.arcs;
    if (q.area_correction) r.step.area_correction = q.area_correction;
    if (q.arc_width) r.step.arc_width = q.arc_width;
    return r;
}

SurfaceRunOptions apply_overrides(const RunOverrides& q, SurfaceRunOptions o, double length_scale,
                                  SettingNames names) {
    const Checker check = apply_shared(q, names, 3, o);
    check.positive(q.volume_drift, {"volume_drift", "--volume-drift"});
    SurfaceContourOptions& c = o.step.contour;
    if (q.depth) {
        c.depth = *q.depth;
        c.eps = eps_for_depth(3, c.depth, length_scale);
    }
    if (q.eps) c.eps = *q.eps;
    if (q.eta) c.eta = *q.eta;
    if (q.area_correction) o.step.volume_correction = q.area_correction;
    if (q.volume_drift) o.volume_drift = *q.volume_drift;
    check.eps_not_below_eta(c.resolved_eps(), o.step.resolved_eta());
    return o;
}

SurfaceRunOptions named_surface_run_options(const SurfaceProblem& p) {
    SurfaceRunOptions o;
    o.t_end = p.t_end;
    o.steps = p.steps;
    o.step.contour = {.depth = p.depth,
                      .refine_passes = SurfaceContourOptions::until_converged,
                      .eps = p.eps,
                      .thin_depth = p.thin_depth};
    return o;
}

namespace {

/// o with N the least multiple of the frames q asks at or above its N, for a user's run whose N
/// q does not give, so that the frames fall at evenly spaced times (a named problem keeps its
/// N, and writes at most a frame a step).
template <class Options>
Options with_steps_a_multiple_of_frames(Options o, const RunOverrides& q, bool named) {
    if (named || q.steps || !q.frames || *q.frames <= 0) return o;
    const std::int64_t f = *q.frames, steps = (o.steps + f - 1) / f * f;
    o.steps = static_cast<int>(std::min<std::int64_t>(steps, setting_range::steps.hi / f * f));
    return o;
}

}  // namespace

RunOptions run_options(const Problem& p, const RunOverrides& q, SettingNames names) {
    RunOptions o = apply_overrides(q, problem_run_options(p), p.length_scale, names);
    // A user's flow field given another extension than its own (direct) has a time error in
    // each step: the steps of the other laws.
    if (p.flow_field && !q.steps && q.extension) {  // (only a user's curves have flow_field)
        o.steps =
            *q.extension == Extension::direct ? detail::flow_field_steps(2) : detail::user_steps(2);
    }
    return with_steps_a_multiple_of_frames(o, q, p.named);
}

SurfaceRunOptions surface_run_options(const SurfaceProblem& p, bool named, double t_start,
                                      const RunOverrides& q, SettingNames names) {
    if (named) return apply_overrides(q, named_surface_run_options(p), 1.0, names);
    SurfaceRunOptions o = default_surface_run_options(p.initial, *p.law, t_start, p.t_end);
    o.step.contour.depth =
        depth_for_domain(3, p.domain.width(), default_domain(bounding_box(p.initial)).width());
    return with_steps_a_multiple_of_frames(apply_overrides(q, o, length_scale(p.initial), names), q,
                                           false);
}

int depth_for_domain(int dim, double domain_width, double default_width) {
    if (!(domain_width > default_width) || !std::isfinite(domain_width / default_width))
        return default_depth;
    // A domain a rounding error wider than the default is the default.
    const int more = static_cast<int>(std::ceil(std::log2(domain_width / default_width) - 1e-9));
    return std::min(default_depth + more, setting_range::depth(dim).hi);
}

bool sets_contour(const RunOverrides& q) {
    return q.depth || q.refine || q.eps || q.eta || q.thin_depth;
}

}  // namespace slc
