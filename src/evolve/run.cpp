// The time loop: steps, vanishing, failures and the run's clocks.
#include "slc/evolve/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/tree/orthtree.hpp"

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

namespace {

/// The process's CPU time (all threads) in whole nanoseconds: a difference of two readings is
/// exact, and seconds() of it the nearest double to the measured seconds.
std::int64_t process_cpu_ns() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

double seconds(std::int64_t ns) { return static_cast<double>(ns) / 1e9; }

void check(const RunOptions& o) {
    if (o.steps < 1) throw InvalidInput(fmt::format("steps must be at least 1, got {}", o.steps));
    if (!std::isfinite(o.t_start) || !std::isfinite(o.t_end) || !(o.t_end > o.t_start)) {
        throw InvalidInput(fmt::format("t-end must be finite and after the start time {}, got {}",
                                       o.t_start, o.t_end));
    }
}

/// The time after n of the N steps: from the step count, not by summing k, so that the last step
/// ends exactly at t_end and a resumed run takes the same steps.
double time_after(const RunOptions& o, int n) {
    const double k = (o.t_end - o.t_start) / o.steps;
    return n == o.steps ? o.t_end : o.t_start + n * k;
}

/// When a flow field carries a vertex of the curves out of the domain within the step (its
/// forward Euler image, x + k u(t, x), outside): the message of LeftDomain, naming the first such
/// vertex. An empty contour from such a step is curves that left the domain, not ones that
/// vanished.
std::optional<std::string> carried_out(const Interface& curves, double t, double k,
                                       const VelocityLaw& law, const Box& domain) {
    if (!law.is_field()) return std::nullopt;
    std::vector<Vec2> u(curves.size());
    law.sample(t, curves.points(), u);
    for (std::size_t i = 0; i < u.size(); ++i) {
        const Vec2 x = curves.point(i), y = x + k * u[i];
        if (domain.contains(y)) continue;
        return fmt::format(
            "the flow carries the curves out of the domain [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] "
            "within a step, ({:.6g}, {:.6g}) to near ({:.6g}, {:.6g}): give a domain that holds "
            "their whole path (--domain, --box), or take more steps (-N)",
            domain.lo.x, domain.hi.x, domain.lo.y, domain.hi.y, x.x, x.y, y.x, y.y);
    }
    return std::nullopt;
}

/// One step in the domain that holds Γ(t): doubled as domain_doublings_for says, then once more
/// each time the contour reaches the edge. Counts the doublings in `result`.
StepResult step_in_growing_domain(const Interface& curves, double t, double k,
                                  const VelocityLaw& law, const Box& domain,
                                  const RunOptions& options, RunResult& counters) {
    const int most = std::min(options.max_domain_doublings,
                              Quadtree::max_supported_depth - options.step.contour.depth);
    for (int j = domain_doublings_for(curves, domain, std::max(most, 0));; ++j) {
        StepOptions o = options.step;
        o.contour.depth += j;
        if (j > 0 && o.embedded.mesh > 0) o.embedded.mesh <<= j;
        try {
            StepResult step = advance(curves, t, k, law, doubled_domain(domain, j), o);
            if (step.curves.empty()) {
                if (const auto out = carried_out(curves, t, k, law, doubled_domain(domain, j)))
                    throw LeftDomain(*out);
            }
            if (j > counters.domain_doublings) {
                if (counters.domain_doublings == 0) counters.domain_grown_at = t;
                counters.domain_doublings = j;
            }
            return step;
        } catch (const LeftDomain&) {
            if (j >= most) throw;
        }
    }
}

/// Throws NumericalFailure when Γ(t) has left the region where the law is known (a velocity
/// given on a grid): the step's curves are dropped, and the run ends with Γ still inside it.
void require_inside_extent(const VelocityLaw& law, const Interface& curves, double t) {
    const std::optional<std::size_t> i = vertex_outside_extent(law, curves);
    if (!i) return;
    const Box b = *law.extent();
    const Vec2 p = curves.point(*i);
    throw NumericalFailure(fmt::format(
        "at t = {} the curves left the region where velocity '{}' is known, [{}, {}] x [{}, {}], "
        "at ({}, {}): give the velocity on a larger grid, or end the run earlier (t-end)",
        t, law.name(), b.lo.x, b.hi.x, b.lo.y, b.hi.y, p.x, p.y));
}

/// A step that broke the law's invariants in every split RunOptions::max_substep_halvings allows.
struct Unstable {
    std::string message;
};

/// The step from Γ(t) (result's) to t_next: whole, or when it breaks the law's invariants
/// (RunOptions::guards) split into 2, 4, ... sub-steps until each keeps them. Adds the G
/// evaluations, vertices and area corrections of every sub-step that was kept to `counters`, and
/// its split to counters.split_steps / most_substeps. A split whose step fails (NumericalFailure:
/// a contour that leaves a fixed domain, say) is retried the same way. Throws Unstable when no
/// split keeps the invariants, and the finest split's NumericalFailure when every split fails.
StepResult guarded_step(const RunResult& result, double t_next, const VelocityLaw& law,
                        const Box& domain, const RunOptions& options, RunResult& counters) {
    const Invariants invariants = law.invariants();
    const double eps = options.step.contour.resolved_eps();
    const double h = std::ldexp(domain.width(), -options.step.contour.depth);
    const GuardBudget budget{.run_length = options.t_end - options.t_start,
                             .resolved_area = std::numbers::pi * h * h,
                             .start_area = invariants.rigid ? counters.start_area : 0.0};
    const int halvings = options.guards ? std::max(options.max_substep_halvings, 0) : 0;
    std::string violation;
    // Γ(t)'s area and length as the step reads them, once: each sub-step's are the one before's
    // after.
    const auto measures = [&](const Interface& curves) {
        const auto [a, l] = step_area_and_length(curves, law, options.step);
        return CurveMeasures{a, l};
    };
    const CurveMeasures start = options.guards ? measures(result.curves) : CurveMeasures{};
    for (int j = 0; j <= halvings; ++j) {
        const int parts = 1 << j;
        StepResult out{result.curves, {}};
        double t = result.t;
        CurveMeasures m0 = start;
        std::size_t g_evals = 0, vertices = 0;
        double corrected = 0.0, lag = 0.0;
        bool kept = true;
        for (int i = 1; i <= parts && !out.curves.empty(); ++i) {
            const double t_to = i == parts ? t_next : result.t + (t_next - result.t) * i / parts;
            StepResult s;
            try {
                s = step_in_growing_domain(out.curves, t, t_to - t, law, domain, options, counters);
                require_inside_extent(law, s.curves, t_to);
            } catch (const LimitExceeded&) {
                throw;  // a setting beyond a limit: smaller steps would not help
            } catch (const NumericalFailure&) {
                // A step too large for the curves' features may fail where smaller ones do not.
                if (j == halvings) throw;
                kept = false;
                break;
            }
            if (options.guards) {
                const CurveMeasures m1 = measures(s.curves);
                if (auto v = invariant_violation(invariants, out.curves, m0, s.curves, m1, t_to - t,
                                                 eps, budget)) {
                    violation = fmt::format("at t = {}: {}", t, *v);
                    kept = false;
                    break;
                }
                if (const auto expected = area_change_expected(invariants, out.curves, m0.area,
                                                               s.curves, t_to - t, budget))
                    lag += (m1.area - m0.area) - *expected;
                m0 = m1;
            }
            g_evals += s.stats.g_evals();
            vertices += s.stats.vertices();
            corrected += s.stats.area_correction;
            out = std::move(s);
            t = t_to;
        }
        if (!kept) continue;
        const double run_lag = counters.area_lag + lag;
        if (options.guards && counters.start_area != 0.0 &&
            std::abs(run_lag) > budget.run_lag_fraction * std::abs(counters.start_area)) {
            throw Unstable{fmt::format(
                "by t = {}: the area has changed by {:.3g} more than the law's rate gives, {:.3g}% "
                "of the {:.3g} at the start: raise the steps N or the depth K",
                t_next, run_lag, 100.0 * run_lag / std::abs(counters.start_area),
                counters.start_area)};
        }
        if (options.guards && invariants.shortens && !out.curves.empty()) {
            // m0: the last sub-step's measures.
            if (const auto growth =
                    growth_above_least(counters.least_length, m0.length, t_next,
                                       budget.run_length_growth, budget.eps_lengths * eps)) {
                throw Unstable{fmt::format(
                    "by t = {:.6g}: the length has grown by {:.3g}% since t = {:.6g} under a law "
                    "that shortens the curves, more than the run's {:g}%: the steps roughen the "
                    "curves; raise the steps N (or the smoothing S of the embedded module), or "
                    "use --geometry arclength",
                    t_next, 100.0 * *growth, counters.least_length.t,
                    100.0 * budget.run_length_growth)};
            }
        }
        if (options.guards && invariants.rigid && !out.curves.empty()) {
            if (counters.rigid_segments == 0) {
                counters.rigid_segments = out.curves.size();
            } else if (static_cast<double>(out.curves.size()) >
                       budget.rigid_segments_growth *
                           static_cast<double>(counters.rigid_segments)) {
                throw Unstable{fmt::format(
                    "by t = {}: the contour needs {} segments where the run's first needed {}, "
                    "but a rigid motion keeps the shape: the steps roughen the curves; use "
                    "--extension direct or raise --eps",
                    t_next, out.curves.size(), counters.rigid_segments)};
            }
        }
        counters.area_lag = run_lag;
        counters.g_evals += g_evals;
        counters.vertices_produced += vertices;
        counters.area_corrected += corrected;
        if (parts > 1) {
            ++counters.split_steps;
            counters.most_substeps = std::max(counters.most_substeps, parts);
        }
        return out;
    }
    throw Unstable{fmt::format("{}, also in {} sub-steps: raise the steps N or the depth K",
                               violation, 1 << halvings)};
}

}  // namespace

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
    if (options.guards && (law.invariants().area_rate_per_curve || law.invariants().rigid))
        start.start_area = step_area(initial, law, options.step);
    return resume(start, law, domain, options, observer);
}

RunResult resume(const RunResult& from, const VelocityLaw& law, const Box& domain,
                 const RunOptions& options, const Observer& observer) {
    check(options);
    require_inside_extent(law, from.curves);
    if (from.steps_done < 0 || from.steps_done >= options.steps) {
        throw InvalidInput(fmt::format("cannot resume after step {} of a run of {} steps",
                                       from.steps_done, options.steps));
    }
    if (from.t != time_after(options, from.steps_done)) {
        throw InvalidInput(fmt::format("cannot resume: t = {} is not the time after step {} ({})",
                                       from.t, from.steps_done,
                                       time_after(options, from.steps_done)));
    }
    RunResult result = from;
    result.status = RunStatus::ok;
    result.message.clear();
    const double wall_before = from.wall_s;
    const double cpu_before = from.cpu_s;
    const auto wall_start = std::chrono::steady_clock::now();
    const std::int64_t cpu_start = process_cpu_ns();
    auto clocks = [&] {
        result.wall_s =
            wall_before +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        result.cpu_s = cpu_before + seconds(process_cpu_ns() - cpu_start);
    };
    for (int n = from.steps_done + 1; n <= options.steps; ++n) {
        const double t_next = time_after(options, n);
        StepResult step;
        const std::int64_t step_cpu_start = process_cpu_ns();
        try {
            step = guarded_step(result, t_next, law, domain, options, result);
        } catch (const NumericalFailure& e) {
            result.status = RunStatus::error;
            result.message = fmt::format("step {} from t = {}: {}", n, result.t, e.what());
            break;
        } catch (const Unstable& e) {
            result.status = RunStatus::unstable;
            result.message = fmt::format("step {} from t = {}: {}", n, result.t, e.message);
            break;
        }
        const double step_cpu_s = seconds(process_cpu_ns() - step_cpu_start);
        result.curves = std::move(step.curves);
        result.t = t_next;
        result.steps_done = n;
        clocks();
        const bool go_on =
            !observer || observer(StepReport{n, options.steps, result.t, &result.curves,
                                             &step.stats, result.wall_s, step_cpu_s, &result});
        if (result.curves.empty()) {
            result.status = RunStatus::vanished;
            break;
        }
        if (!go_on && n < options.steps) {
            result.status = RunStatus::interrupted;
            break;
        }
    }
    clocks();
    return result;
}

}  // namespace slc
