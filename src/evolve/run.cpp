// The time loop of curves (paper §4.3): the hooks of time_loop.hpp for d = 2 (the area and length
// the guards measure, the law's run-wide budgets, the counters of RunResult), run() and resume().
#include "slc/evolve/run.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/velocity/laws.hpp"
#include "start_check.hpp"
#include "time_loop.hpp"

namespace slc {

const char* to_string(RunStatus status) {
    switch (status) {
        case RunStatus::ok:
            return "ok";
        case RunStatus::vanished:
            return "vanished";
        case RunStatus::interrupted:
            return "interrupted";
        case RunStatus::unstable:
            return "unstable";
        case RunStatus::broken:
            return "broken";
        default:
            return "error";
    }
}

namespace detail {

/// Curves: the guards measure the area and length as the step reads them (guards.hpp), and with
/// the guards off still check every step, noting the first break (status broken).
template <>
class LoopHooks<2> {
public:
    using Options = RunOptions;
    using Result = RunResult;
    using StepResult = slc::StepResult;
    using Report = StepReport;
    using Observer = slc::Observer;

    static constexpr int max_depth = Quadtree::max_supported_depth;
    static constexpr const char* noun = "the curves";
    static constexpr const char* shape_name = "curves";
    static constexpr const char* leave = "leave";  ///< the verb with the noun
    static constexpr const char* possessive = "their";

    static Interface& shape(RunResult& r) { return r.curves; }
    static const Interface& shape(const RunResult& r) { return r.curves; }
    static Interface& shape(StepResult& s) { return s.curves; }
    /// Its particles: the counterclockwise curves.
    static std::size_t components(const Interface& c) {
        std::size_t outer = 0;
        for (std::size_t j = 0; j < c.curve_count(); ++j) outer += signed_area(c.curve(j)) > 0;
        return outer;
    }

    /// The step's options in the domain doubled j times: K and the embedded module's mesh M a
    /// level finer, the same finest cell.
    static StepOptions step_options(const RunOptions& options, int j) {
        StepOptions o = options.step;
        o.contour.depth += j;
        if (j > 0 && o.embedded.mesh > 0) o.embedded.mesh <<= j;
        return o;
    }

    /// A sub-step from t to t_to takes k = t_to − t, so that the last ends at t_next exactly.
    static double substep_length(double, double, int, double t, double t_to) { return t_to - t; }

    LoopHooks(const VelocityLaw& law, const Box& domain, const RunOptions& options)
        : law_(law),
          domain_(domain),
          options_(options),
          invariants_(law.invariants()),
          eps_(options.step.contour.resolved_eps()) {
        if (!(options.area_drift > 0.0) || !std::isfinite(options.area_drift)) {
            throw InvalidInput(
                fmt::format("area_drift must be a positive fraction, got {}", options.area_drift));
        }
        if (!(options.area_rate_drift >= 0.0) || !std::isfinite(options.area_rate_drift)) {
            throw InvalidInput(fmt::format("area_rate_drift must be a fraction, 0 or more, got {}",
                                           options.area_rate_drift));
        }
        if (!(options.area_step_share >= 0.0) || !std::isfinite(options.area_step_share)) {
            throw InvalidInput(
                fmt::format("area_step_share must be 0 or more, got {}", options.area_step_share));
        }
        const double h = finest_cell(domain, options.step.contour);
        budget_ = GuardBudget{.run_lag_fraction = options.area_drift,
                              .run_rate_fraction = options.area_rate_drift,
                              .step_share = options.area_step_share,
                              .run_length = options.t_end - options.t_start,
                              .resolved_area = std::numbers::pi * h * h};
    }

    using Start = CurveMeasures;

    /// Γ(t)'s area and length as the step reads them, once: each sub-step's are the one before's
    /// after.
    CurveMeasures start(const Interface& curves) const { return measures(curves); }

    /// What one split of a step did.
    struct Attempt {
        CurveMeasures m0;  ///< the measures before the next sub-step
        std::size_t g_evals = 0, vertices = 0;
        double corrected = 0.0, lag = 0.0, run_lag = 0.0;
        double law_change = 0.0, run_law_change = 0.0;  ///< the law's area change, as lag
    };

    /// Checks the sub-step from `before` at t to s, and counts it in a: its break with the guards
    /// on, noted in r off.
    std::optional<std::string> record(Attempt& a, const Interface& before, const StepResult& s,
                                      double t, double k, RunResult& r) const {
        // Checked with the guards on or off: off, the step is kept whole and its break noted.
        const CurveMeasures m1 = measures(s.curves);
        if (auto v =
                invariant_violation(invariants_, before, a.m0, s.curves, m1, k, eps_, budget(r))) {
            std::string why = fmt::format("at t = {}: {}", t, *v);
            if (options_.guards) return why;
            note_broken(r, why + ": raise the steps N or the depth K");
        }
        if (const auto expected =
                area_change_expected(invariants_, before, a.m0.area, s.curves, k, budget(r))) {
            a.lag += (m1.area - a.m0.area) - *expected;
            a.law_change += *expected;
        }
        a.m0 = m1;
        note_cells(r, s.stats.predictor, t + k);
        note_cells(r, s.stats.corrector, t + k);
        a.g_evals += s.stats.g_evals();
        a.vertices += s.stats.vertices();
        a.corrected += s.stats.area_correction;
        return std::nullopt;
    }

    /// The run's area lag, its length above the least (a law that shortens the
    /// curves) and its segments (a rigid motion), after the step to t_next ends at `curves`.
    std::optional<BudgetBreach> run_budget(Attempt& a, const Interface& curves, double t_next,
                                           RunResult& r) const;

    /// Adds what the kept split did to r.
    static void commit(const Attempt& a, RunResult& r) {
        r.area_lag = a.run_lag;
        r.area_law_change = a.run_law_change;
        r.g_evals += a.g_evals;
        r.vertices_produced += a.vertices;
        r.area_corrected += a.corrected;
    }

    static void check_start(const RunResult&) {}

    /// A step that broke the law in every split: the settings that may keep it. The extensions
    /// from the nearest point carry a vertex's velocity to every point nearest it, so their W
    /// jumps across the normals at the polygon's corners, where the direct extension's is the
    /// law's own.
    std::string unstable_after_splits(const std::string& violation, int pieces, double) const {
        if (flows_directly(law_, options_.step)) {
            return fmt::format(
                "{}, also in {} sub-steps: raise the depth K, or take fewer steps N ({})",
                violation, pieces, fewer_steps_reason);
        }
        const bool extended = options_.step.resolved_extension(law_) != Extension::direct &&
                              (law_.is_normal_law() || law_.is_field());
        return fmt::format("{}, also in {} sub-steps: raise the steps N or the depth K{}",
                           violation, pieces, extended ? ", or use --extension direct" : "");
    }
    static std::string at_step(int n, double t, const std::string& why) {
        return fmt::format("step {} from t = {}: {}", n, t, why);
    }
    static std::string step_failed(int n, double t, const char* what) {
        return at_step(n, t, what);
    }

private:
    CurveMeasures measures(const Interface& curves) const {
        const auto [a, l] = step_area_and_length(curves, law_, options_.step, domain_);
        return CurveMeasures{a, l};
    }
    /// The budget, with a rigid motion's area at the start of the run.
    GuardBudget budget(const RunResult& r) const {
        GuardBudget b = budget_;
        b.start_area = invariants_.rigid ? r.start_area : 0.0;
        return b;
    }

    const VelocityLaw& law_;
    Box domain_;  ///< the run's domain, whose finest cell sets where arcs read Γ as smooth
    const RunOptions& options_;
    Invariants invariants_;
    double eps_;
    GuardBudget budget_;
};

std::optional<BudgetBreach> LoopHooks<2>::run_budget(Attempt& a, const Interface& curves,
                                                     double t_next, RunResult& r) const {
    a.run_lag = r.area_lag + a.lag;
    const GuardBudget b = budget(r);
    if (r.start_area != 0.0 && std::abs(a.run_lag) > b.run_lag_fraction * std::abs(r.start_area)) {
        return BudgetBreach{
            fmt::format("by t = {}: the area has changed by {:.3g} more than the law's rate "
                        "gives, {:.3g}% of the {:.3g} at the start: raise the steps N or the "
                        "depth K",
                        t_next, a.run_lag, 100.0 * a.run_lag / std::abs(r.start_area),
                        r.start_area),
            true};
    }
    a.run_law_change = r.area_law_change + a.law_change;
    // Beyond one step's tolerance of the contours (a.m0: the last sub-step's measures).
    if (b.run_rate_fraction > 0.0 &&
        std::abs(a.run_lag) >
            b.run_rate_fraction * std::abs(a.run_law_change) + b.eps_lengths * eps_ * a.m0.length) {
        return BudgetBreach{
            fmt::format("by t = {}: the area has changed by {:.3g} where the law's rate gives "
                        "{:.3g}, {:.3g}% off, more than the run's {:g}%: raise the steps N or the "
                        "depth K",
                        t_next, a.run_law_change + a.run_lag, a.run_law_change,
                        100.0 * std::abs(a.run_lag / a.run_law_change),
                        100.0 * b.run_rate_fraction),
            true};
    }
    if (invariants_.shortens && !curves.empty()) {
        // a.m0: the last sub-step's measures.
        if (const auto growth = growth_above_least(r.least_length, a.m0.length, t_next,
                                                   b.run_length_growth, b.eps_lengths * eps_)) {
            // A law that fits its own smooth curves (the potential laws) has no geometry module
            // to change.
            const char* remedy = law_.needs().smooth
                                     ? "raise the steps N or the depth K"
                                     : "raise the steps N (or the smoothing S of the embedded "
                                       "module), or use --geometry arclength";
            return BudgetBreach{fmt::format(
                "by t = {:.6g}: the length has grown by {:.3g}% since t = {:.6g} under a law "
                "that shortens the curves, more than the run's {:g}%: the steps roughen the "
                "curves; {}",
                t_next, 100.0 * *growth, r.least_length.t, 100.0 * b.run_length_growth, remedy)};
        }
    }
    if (invariants_.rigid && !curves.empty()) {
        if (r.rigid_segments == 0) {
            r.rigid_segments = curves.size();
        } else if (static_cast<double>(curves.size()) >
                   b.rigid_segments_growth * static_cast<double>(r.rigid_segments)) {
            return BudgetBreach{fmt::format(
                "by t = {}: the contour needs {} segments where the run's first needed {}, but a "
                "rigid motion keeps the shape: the steps roughen the curves; use --extension "
                "direct or raise --eps",
                t_next, curves.size(), r.rigid_segments)};
        }
    }
    // The step's own lag beyond its share of the run's (a.m0: the last sub-step's measures):
    // finer sub-steps while they help, then the best kept (guarded_step).
    if (b.step_share > 0.0 && r.start_area != 0.0 && options_.t_end > r.t) {
        const double left = b.run_lag_fraction * std::abs(r.start_area) - std::abs(r.area_lag);
        const double share =
            b.step_share * left * (t_next - r.t) / (options_.t_end - r.t) + eps_ * a.m0.length;
        if (std::abs(a.lag) > share) {
            return BudgetBreach{
                fmt::format("by t = {}: the step's area lag {:.3g} is beyond its share {:.3g}",
                            t_next, a.lag, share),
                true, std::abs(a.lag)};
        }
    }
    return std::nullopt;
}

}  // namespace detail

Box doubled_domain(const Box& domain, int times) {
    if (times == 0) return domain;
    return Box::square(domain.center(), std::ldexp(0.5 * domain.width(), times));
}

int domain_doublings_for(const Interface& curves, const Box& domain, int max_doublings) {
    if (curves.empty()) return 0;
    const Box b = bounding_box(curves.points());
    for (int j = 0; j < max_doublings; ++j) {
        const Box d = doubled_domain(domain, j);
        const double margin = 0.125 * d.width();
        if (b.lo.x - d.lo.x >= margin && b.lo.y - d.lo.y >= margin && d.hi.x - b.hi.x >= margin &&
            d.hi.y - b.hi.y >= margin)
            return j;
    }
    return max_doublings;
}

RunResult run(const Interface& initial, const VelocityLaw& law, const Box& domain,
              const RunOptions& options, const Observer& observer) {
    RunResult start;  // resume() checks the options
    start.curves = initial;
    start.t = options.t_start;
    start.thin_depth = options.step.contour.thin_depth;
    if (options.check_start && !initial.empty()) {
        // A flow field at rest: G(x) = F(x), so the step's contour is the curves' own.
        const Translation rest({0.0, 0.0});
        const auto read = [&](int thin) {
            StepOptions o = options.step;
            o.contour.thin_depth = thin;
            return advance(initial, options.t_start, 1.0, rest, domain, o).curves;
        };
        const ContourOptions& c = options.step.contour;
        const detail::StartTolerance keep{
            .cell = finest_cell(domain, c),
            .measure = step_area(initial, rest, options.step, domain),
            .tolerance = detail::start_measure_tolerance(c, length(initial))};
        start.thin_depth =
            detail::start_as_given<2>(initial, domain, c.depth, c.thin_depth, keep, read).first;
    }
    if (law.invariants().area_rate_per_curve || law.invariants().rigid)
        start.start_area = step_area(initial, law, options.step, domain);
    return resume(start, law, domain, options, observer);
}

RunResult resume(const RunResult& from, const VelocityLaw& law, const Box& domain,
                 const RunOptions& options, const Observer& observer) {
    return detail::time_loop<2>(from, law, domain, options, observer);
}

}  // namespace slc
