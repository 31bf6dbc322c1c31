// The time loop of surfaces (paper §4.3 with d = 3, DESIGN §8): the hooks of time_loop.hpp for
// d = 3 (the volume, area, components and genus the guards check, the notes of a run with its
// guards off, the counters of SurfaceRunResult), the guards of one step
// (surface_invariant_violation), run() and resume().
#include "slc/evolve/surface_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "slc/core/error.hpp"
#include "slc/tree/tetrahedralization.hpp"
#include "slc/velocity/surface_laws.hpp"
#include "start_check.hpp"
#include "thin_parts.hpp"
#include "time_loop.hpp"

namespace slc {
namespace detail {

/// Surfaces: the guards check volume, area, components and genus (surface_invariant_violation),
/// and with the guards off still check every step, noting the first break (status broken).
template <>
class LoopHooks<3> {
public:
    using Options = SurfaceRunOptions;
    using Result = SurfaceRunResult;
    using StepResult = SurfaceStepResult;
    using Report = SurfaceStepReport;
    using Observer = SurfaceObserver;

    static constexpr int max_depth = max_tetrahedralized_depth;
    static constexpr const char* noun = "the surface";
    static constexpr const char* shape_name = "surface";
    static constexpr const char* leave = "leaves";  ///< the verb with the noun
    static constexpr const char* possessive = "its";

    static Surface& shape(SurfaceRunResult& r) { return r.surface; }
    static const Surface& shape(const SurfaceRunResult& r) { return r.surface; }
    static Surface& shape(SurfaceStepResult& s) { return s.surface; }
    static std::size_t components(const Surface& s) { return component_count(s); }

    /// The step's options in the domain doubled j times: K a level deeper, the same finest cell.
    static SurfaceStepOptions step_options(const SurfaceRunOptions& options, int j) {
        SurfaceStepOptions o = options.step;
        o.contour.depth += j;
        return o;
    }

    /// NOTE: the sub-steps of a surface's step keep the equal length (t_next − t0)/parts they
    /// have always had (curves take t_to − t): the two differ in the last bit, and the runs of
    /// either stay what they were.
    static double substep_length(double t0, double t_next, int parts, double, double) {
        return (t_next - t0) / parts;
    }

    LoopHooks(const SurfaceVelocityLaw& law, const Box3&, const SurfaceRunOptions& options)
        : options_(options),
          invariants_(law.invariants()),
          steps_(flows_directly(law, options.step)
                     ? fmt::format("take fewer steps (-N: {})", fewer_steps_reason)
                     : "take more steps (-N)"),
          eps_(options.step.contour.resolved_eps()),
          until_converged_(options.step.contour.refine_passes ==
                           SurfaceContourOptions::until_converged) {}

    struct Start {};
    Start start(const Surface&) const { return {}; }

    /// What one split of a step did.
    struct Attempt {
        Start start;
        double corrected = 0.0;
        bool unconverged = false;
        double residual = 0.0;
    };

    /// Counts the sub-step from `before` at t to s (its G evaluations in r whether or not the
    /// split is kept), and checks it: its break with the guards on, noted in r off.
    std::optional<std::string> record(Attempt& a, const Surface& before, const SurfaceStepResult& s,
                                      double t, double k, SurfaceRunResult& r) const;

    /// The volume's drift since the start (a law that keeps it) and the area above the least (a
    /// law that shrinks it), after the step to t_next ends at `surface`.
    std::optional<BudgetBreach> run_budget(Attempt& a, const Surface& surface, double t_next,
                                           SurfaceRunResult& r) const;

    /// Adds what the kept split did to r.
    static void commit(const Attempt& a, SurfaceRunResult& r) {
        r.volume_corrected += a.corrected;
        if (a.unconverged) {
            ++r.unconverged_steps;
            r.largest_residual = std::max(r.largest_residual, a.residual);
        }
    }

    static void check_start(const SurfaceRunResult& from) {
        if (from.surface.empty()) throw InvalidInput("the surface to resume has no triangles");
    }

    std::string unstable_after_splits(const std::string& violation, int pieces, double t0) const {
        return fmt::format(
            "at t = {:.6g}: {} (also in {} sub-steps); {} or refine the contours "
            "(-K, --eps)",
            t0, violation, pieces, steps_);
    }
    static std::string at_step(int, double, const std::string& why) { return why; }
    static std::string step_failed(int, double t, const char* what) {
        return fmt::format("at t = {:.6g}: {}", t, what);
    }

private:
    const SurfaceRunOptions& options_;
    Invariants invariants_;
    /// What to do with the steps when the law breaks (flows_directly).
    std::string steps_;
    double eps_;
    bool until_converged_;
};

std::optional<std::string> LoopHooks<3>::record(Attempt& a, const Surface& before,
                                                const SurfaceStepResult& s, double t, double k,
                                                SurfaceRunResult& r) const {
    r.g_evals += s.stats.g_evals();
    note_cells(r, s.stats.predictor, t + k);
    note_cells(r, s.stats.corrector, t + k);
    a.corrected += s.stats.volume_correction;
    if (until_converged_ && !s.surface.empty() && !s.stats.corrector.converged) {
        a.unconverged = true;
        a.residual = std::max(a.residual, s.stats.corrector.residual);
    }
    auto v = surface_invariant_violation(invariants_, before, s.surface, k, eps_);
    if (!v || options_.guards) return v;
    // Without guards the step is kept whole: noted, not split.
    note_broken(
        r, fmt::format("at t = {:.6g}: {}; {} or refine the contours (-K, --eps)", t, *v, steps_));
    return std::nullopt;
}

std::optional<BudgetBreach> LoopHooks<3>::run_budget(Attempt&, const Surface& surface,
                                                     double t_next, SurfaceRunResult& r) const {
    std::optional<std::string> why;
    if (invariants_.keeps_area && !surface.empty()) {
        const double drift = volume(surface) / r.volume_initial - 1.0;
        if (std::abs(drift) > options_.volume_drift) {
            why = fmt::format(
                "at t = {:.6g}: the volume drifted by {:.3g}% since the start under a law that "
                "keeps it (more than {:.3g}%); {}, refine the contours (-K, --eps) or allow "
                "more drift (--volume-drift)",
                t_next, 100.0 * drift, 100.0 * options_.volume_drift, steps_);
            if (options_.guards) return BudgetBreach{*why};
        }
    }
    if (invariants_.shortens && !surface.empty()) {
        if (const auto growth =
                growth_above_least(r.least_area, area(surface), t_next, options_.area_growth,
                                   20.0 * eps_ * std::sqrt(r.least_area.value));
            growth && !why) {
            why = fmt::format(
                "at t = {:.6g}: the area has grown by {:.3g}% since t = {:.6g} under a law that "
                "shrinks it, more than the run's {:g}%: the steps roughen the surface; take more "
                "steps (-N) or refine the contours (-K, --eps)",
                t_next, 100.0 * *growth, r.least_area.t, 100.0 * options_.area_growth);
        }
    }
    // Surfaces' drifts end the run rather than split the step, each of whose sub-steps costs a
    // whole contour.
    if (why) return BudgetBreach{*why};
    return std::nullopt;
}

}  // namespace detail

Surface surface_as_read(const Surface& s, const Box3& domain, SurfaceRunOptions& options) {
    // A flow field at rest: G(x) = F(x), so the step's contour is the surface's own.
    const SurfaceTranslation rest({0.0, 0.0, 0.0});
    const auto read = [&](int thin) {
        SurfaceStepOptions o = options.step;
        o.contour.thin_depth = thin;
        // The given surface read at rest is flat where the reading finds a corner: its creases
        // are the input's, and the start keeps them sharp to ε (the steps' contours do not cut
        // them: docs/surfaces.md, "Sharp edges in a run's steps").
        o.contour.creases = true;
        // Its topology is known: the contour keeps it beside sharp edges and points, where the
        // signs of G at vertices a hair from the zero set would cut specks or open handles.
        o.contour.keep_topology = shape_topology(s);
        Surface contour = advance(s, options.t_start, 1.0, rest, domain, o).surface;
        if (contour.empty() && !s.empty()) {
            const Box3 b = bounding_box(s);
            throw InvalidInput(fmt::format(
                "the surface, {:.3g} across, is too small for the contours to see: the finest "
                "cell at K = {} in the domain {:.3g} wide is {:.3g}; raise K (-K) or give a "
                "smaller domain",
                std::max({b.extent(0), b.extent(1), b.extent(2)}), options.step.contour.depth,
                domain.width(), std::ldexp(domain.width(), -options.step.contour.depth)));
        }
        return contour;
    };
    const SurfaceContourOptions& c = options.step.contour;
    const detail::StartTolerance keep{.cell = std::ldexp(domain.width(), -c.depth),
                                      .measure = step_volume(s, options.step),
                                      .tolerance = detail::start_measure_tolerance(c, area(s))};
    auto [thin, contour] = detail::start_as_given<3>(s, domain, c.depth, c.thin_depth, keep, read);
    options.step.contour.thin_depth = thin;
    return std::move(contour);
}

Box3 doubled_domain(const Box3& domain, int times) {
    if (times == 0) return domain;
    return Box3::cube(domain.center(), std::ldexp(0.5 * domain.width(), times));
}

int domain_doublings_for(const Surface& s, const Box3& domain, int max_doublings) {
    if (s.empty() || max_doublings == 0) return 0;
    const Box3 b = bounding_box(s);
    for (int j = 0; j < max_doublings; ++j) {
        const Box3 d = doubled_domain(domain, j);
        if (d.inflated(-0.125 * d.width()).contains(b)) return j;
    }
    return max_doublings;
}

std::optional<std::string> surface_invariant_violation(const Invariants& law, const Surface& before,
                                                       const Surface& after, double k, double eps) {
    if (before.empty()) return std::nullopt;
    constexpr double fraction = 1e-2, eps_multiple = 20.0;
    const double a0 = area(before);
    if (after.empty()) {
        if (law.keeps_area) return "the surface vanished under a law that keeps its volume";
        if (law.cannot_vanish) return "the surface vanished under a law that only grows it";
        if (law.rigid) return "the surface vanished under a rigid motion";
        return std::nullopt;
    }
    if (law.rigid) {
        const std::size_t c0 = component_count(before), c1 = component_count(after);
        if (c0 != c1) {
            return fmt::format("a rigid motion changed the number of components from {} to {}", c0,
                               c1);
        }
        const long long g0 = genus(before), g1 = genus(after);
        if (g0 != g1) return fmt::format("a rigid motion changed the genus from {} to {}", g0, g1);
    }
    if (auto v = shape_parts_violation(law, before, after)) return v;
    if (law.cannot_split && !law.rigid) {
        const std::size_t c0 = component_count(before), c1 = component_count(after);
        if (c1 > c0) {
            return fmt::format(
                "the number of components rose from {} to {} under a law that cannot split the "
                "surface (a part thinner than the contours resolve tore)",
                c0, c1);
        }
        // A smooth flow moves the surface by a diffeomorphism: no hole opens or closes.
        const long long g0 = genus(before), g1 = genus(after);
        if (c1 == c0 && g1 != g0) {
            return fmt::format(
                "the genus changed from {} to {} under a law that cannot tear or join the "
                "surface (a part thinner than the contours resolve tore)",
                g0, g1);
        }
    }
    if (law.keeps_area) {
        const double v0 = volume(before), v1 = volume(after);
        const double tolerance =
            std::max(fraction * std::max(std::abs(v0), std::abs(v1)), eps_multiple * eps * a0);
        if (std::abs(v1 - v0) > tolerance) {
            return fmt::format(
                "the volume changed by {:.3g}% in one step under a law that keeps it",
                100.0 * (v1 - v0) / std::abs(v0));
        }
    }
    if (law.cannot_vanish && volume(after) < volume(before) - eps_multiple * eps * a0)
        return "the volume fell in one step under a law that only grows the surface";
    if (law.shortens) {
        const double a1 = area(after);
        if (a1 > a0 * (1.0 + fraction) + eps_multiple * eps * std::sqrt(a0)) {
            return fmt::format("the area grew by {:.3g}% in one step under a law that shrinks it",
                               100.0 * (a1 - a0) / a0);
        }
    }
    // A constant normal speed s offsets the surface by d = s k in the step: the area of the
    // offset by x is A₀ + x ∫H dA + 2π χ x² (Steiner's tube formula, χ the Euler
    // characteristic), so the volume it sweeps, its integral to d, is d (A₀ + A₁)/2 − π χ d³/3,
    // exactly, while the offset stays smooth. A component that merges or vanishes within the
    // step changes the area abruptly, and the formula does not hold across it.
    if (law.volume_rate_per_area && component_count(before) == component_count(after)) {
        constexpr double rate_fraction = 0.1;
        const double d = *law.volume_rate_per_area * k;
        const auto chi = static_cast<double>(euler_characteristic(before));
        const double expected =
            d * 0.5 * (a0 + area(after)) - std::numbers::pi * chi * d * d * d / 3.0;
        const double change = volume(after) - volume(before);
        if (std::abs(change - expected) >
            std::max(rate_fraction * std::abs(expected), eps_multiple * eps * a0)) {
            return fmt::format(
                "the volume changed by {:.3g} in one step where the law's speed moves it by {:.3g} "
                "(the volume of the offset by speed times k)",
                change, expected);
        }
    }
    return std::nullopt;
}

std::optional<double> thinnest_new_component(const Surface& before, const Surface& after) {
    const auto part = detail::thinnest_new_part<3>(before, after);
    if (!part) return std::nullopt;
    return part->thickness;
}

SurfaceRunResult run(const Surface& initial, const SurfaceVelocityLaw& law, const Box3& domain,
                     const SurfaceRunOptions& options, const SurfaceObserver& observer) {
    if (initial.empty()) throw InvalidInput("the initial surface has no triangles");
    SurfaceRunResult start;
    start.surface = initial;
    start.t = options.t_start;
    start.volume_initial = volume(initial);
    return resume(start, law, domain, options, observer);
}

SurfaceRunResult resume(const SurfaceRunResult& from, const SurfaceVelocityLaw& law,
                        const Box3& domain, const SurfaceRunOptions& options,
                        const SurfaceObserver& observer) {
    return detail::time_loop<3>(from, law, domain, options, observer);
}

}  // namespace slc
