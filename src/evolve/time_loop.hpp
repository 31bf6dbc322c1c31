// The time loop of curves and surfaces, written once over the dimension (internal to evolve; paper
// §4.3, DESIGN §8): N steps of advance() from t_start to t_end, each in a domain that grows when
// the interface nears its edge, each split into 2, 4, ... sub-steps when it breaks what the law
// keeps, the run's statuses, clocks and observer, and resume() from a step. What differs between
// the dimensions (the invariants each law keeps, area against volume, what a step returns and how
// the messages read) comes from LoopHooks<dim>, which run.cpp (dim 2) and surface_run.cpp (dim 3)
// define before they call time_loop<dim>().
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/core/box3.hpp"
#include "slc/core/error.hpp"
#include "slc/core/stop.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/evolve/run.hpp"
#include "start_check.hpp"
#include "step_common.hpp"
#include "thin_parts.hpp"
#include "user_defaults.hpp"

namespace slc::detail {

/// Notes in r the finest cell of a contour of the step that ends at t, and whether its thin cells
/// reached their budget (RunTotals::finest_cell, thin_budget_at); c is ContourStats or
/// SurfaceContourStats.
template <class ContourStatsT>
void note_cells(RunTotals& r, const ContourStatsT& c, double t) {
    if (c.finest_cell > 0.0 && (r.finest_cell == 0.0 || c.finest_cell < r.finest_cell)) {
        r.finest_cell = c.finest_cell;
        r.finest_t = t;
        r.finest_at.clear();
        constexpr int dim = std::is_same_v<decltype(c.finest_at), Vec2> ? 2 : 3;
        for (int i = 0; i < dim; ++i) r.finest_at.push_back(c.finest_at[i]);
    }
    if (c.thin_budget_reached && std::isnan(r.thin_budget_at)) r.thin_budget_at = t;
}

/// With the guards off, the first break is kept (a coarse run whose interface tears, measured
/// anyway): it is the message of a run that vanishes, and makes a run that ends broken.
inline void note_broken(RunTotals& r, std::string why) {
    if (r.broken.empty()) r.broken = std::move(why);
}

/// What differs between curves (dim 2) and surfaces (dim 3): the types of a run (Options, Result,
/// StepResult, Report, Observer, Law, Region, Shape), the step's options in a grown domain, the
/// guards of one step and of the run, and the wording of messages. Specialised where it is used.
template <int dim>
class LoopHooks;

/// A run beyond one of its budgets (LoopHooks::run_budget): why, and whether the step is split
/// into sub-steps to keep it (a drift that smaller steps make smaller, as a law's area rate
/// missed) or the run ends there (steps that roughen the interface). A share (a step beyond its
/// share of a budget the run still keeps) is split only while the splits take `excess` down,
/// and never ends the run.
struct BudgetBreach {
    std::string message;
    bool split = false;
    double excess = 0.0;  ///< a share's measure of the step beyond it (0: not a share)
    bool share() const { return excess > 0.0; }
};

/// The process's CPU time (all threads) in whole nanoseconds: a difference of two readings is
/// exact, and seconds() of it the nearest double to the measured seconds.
inline std::int64_t process_cpu_ns() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

inline double seconds(std::int64_t ns) { return static_cast<double>(ns) / 1e9; }

/// Throws InvalidInput for options no run can take (the same for curves and surfaces).
template <class Options>
void check_run_options(const Options& o) {
    if (o.steps < 1) throw InvalidInput(fmt::format("steps must be at least 1, got {}", o.steps));
    if (!std::isfinite(o.t_start) || !std::isfinite(o.t_end) || !(o.t_end > o.t_start)) {
        throw InvalidInput(fmt::format("t-end must be finite and after the start time {}, got {}",
                                       o.t_start, o.t_end));
    }
    if (o.max_substep_halvings < 0 || o.max_substep_halvings > 10) {
        throw InvalidInput(
            fmt::format("max_substep_halvings must be in 0..10, got {}", o.max_substep_halvings));
    }
    if (o.max_domain_doublings < 0) {
        throw InvalidInput(fmt::format("max_domain_doublings must not be negative, got {}",
                                       o.max_domain_doublings));
    }
}

/// The time after n of the N steps: from the step count, not by summing k, so that the last step
/// ends exactly at t_end and a resumed run takes the same steps.
template <class Options>
double time_after(const Options& o, int n) {
    const double k = (o.t_end - o.t_start) / o.steps;
    return n == o.steps ? o.t_end : o.t_start + n * k;
}

/// "[a, b] x [c, d]" (and "x [e, f]" in space), for messages; region_text6 with 6 digits.
inline std::string region_text(const Box& b) {
    return fmt::format("[{}, {}] x [{}, {}]", b.lo.x, b.hi.x, b.lo.y, b.hi.y);
}
inline std::string region_text(const Box3& b) {
    return fmt::format("[{}, {}] x [{}, {}] x [{}, {}]", b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z,
                       b.hi.z);
}
inline std::string region_text6(const Box& b) {
    return fmt::format("[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]", b.lo.x, b.hi.x, b.lo.y, b.hi.y);
}
inline std::string region_text6(const Box3& b) {
    return fmt::format("[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]", b.lo.x, b.hi.x,
                       b.lo.y, b.hi.y, b.lo.z, b.hi.z);
}

/// When a flow field carries a vertex of `shape` out of the domain within the step (its image
/// at t + k, traced forward by the Runge–Kutta rule in max_departure_substeps substeps, outside):
/// the message of LeftDomain, naming the first such vertex. An empty contour from such a step is
/// an interface that left the domain, not one that vanished. (A forward Euler image misses a
/// long step's: a circle of radius 0.0034 carried by LeVeque's vortex for 0.8 of its period 8
/// left its domain with its Euler image inside, and the step read as the circle vanishing.)
template <int dim>
std::optional<std::string> carried_out(const ShapeOf<dim>& shape, double t, double k,
                                       const BasicVelocityLaw<dim>& law,
                                       const RegionOf<dim>& domain) {
    using H = LoopHooks<dim>;
    if (!law.is_field()) return std::nullopt;
    const auto points = vertex_points(shape);
    // Feet "from t back to t + k" (a negative k) are the images at t + k of the points at t;
    // where the field is not known along the way (a lattice's), the Euler images x + k u(t, x).
    std::vector<PointOf<dim>> images;
    try {
        images = runge_kutta_feet(law, t + k, -k, points, max_departure_substeps);
    } catch (const NumericalFailure&) {
        images.resize(points.size());
        law.sample(t, points, images);
        for (std::size_t i = 0; i < images.size(); ++i) images[i] = points[i] + k * images[i];
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        const auto x = points[i], y = images[i];
        if (domain.contains(y)) continue;
        return fmt::format(
            "the flow carries {} out of the domain {} within a step, {} to near {}: give a domain "
            "that holds {} whole path (--domain, --box), or take more steps (-N)",
            H::noun, region_text6(domain), point_text6(x), point_text6(y), H::possessive);
    }
    return std::nullopt;
}

/// Throws (as Error) when a vertex of `shape` lies outside the region where the law is known (a
/// velocity given on a grid), with the message `what(region, index, vertex)`.
template <class Error, int dim, class What>
void check_extent(const BasicVelocityLaw<dim>& law, const ShapeOf<dim>& shape, What what) {
    const auto extent = law.extent();
    if (!extent) return;
    const auto points = vertex_points(shape);
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!extent->contains(points[i])) throw Error(what(region_text(*extent), i, points[i]));
}

/// The step from `shape` at t to t + k in the domain that holds it: doubled the fewest times that
/// keep its bounding box an eighth of the doubled width from the edge (domain_doublings_for), then
/// once more each time the contour reaches the edge (max_domain_doublings), K a level deeper per
/// doubling. Records the doublings in `counters`.
template <int dim>
auto step_in_growing_domain(const ShapeOf<dim>& shape, double t, double k,
                            const BasicVelocityLaw<dim>& law, const RegionOf<dim>& domain,
                            const typename LoopHooks<dim>::Options& options,
                            typename LoopHooks<dim>::Result& counters) {
    using H = LoopHooks<dim>;
    const int most =
        std::min(options.max_domain_doublings, H::max_depth - options.step.contour.depth);
    for (int j = domain_doublings_for(shape, domain, std::max(most, 0));; ++j) {
        try {
            typename H::StepResult step =
                advance(shape, t, k, law, doubled_domain(domain, j), H::step_options(options, j));
            if (H::shape(step).empty()) {
                if (const auto out = carried_out<dim>(shape, t, k, law, doubled_domain(domain, j)))
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

/// A step that broke what the law keeps in every split max_substep_halvings allows, or a run
/// beyond the law's budget (its message as the run reports it, before LoopHooks::at_step).
struct Unstable {
    std::string message;
};

/// A sub-step's new topology as the contours at its thin depth give it, confirmed by those two
/// levels deeper (confirm_topology): the sub-step to keep, or why it cannot be.
template <int dim>
struct Confirmed {
    typename LoopHooks<dim>::StepResult step;
    std::optional<std::string> unresolved;
};

/// " near (x, y[, z])", the centre of a finest cell of the step's contours (ContourStats::
/// finest_at): where thin cells went deepest, or nothing when none did.
template <class StepResult>
std::string finest_place(const StepResult& s) {
    const auto& c = s.stats.corrector.finest_cell > 0.0 ? s.stats.corrector : s.stats.predictor;
    return c.finest_cell > 0.0 ? " near " + point_text6(c.finest_at) : std::string();
}

/// Whether the step's contours left cells that bend whole, their thin cells at their budget
/// (contouring::thin_cell_budget): such contours are the same at any thin depth.
template <class StepResult>
bool at_budget(const StepResult& s) {
    return s.stats.predictor.thin_budget_reached || s.stats.corrector.thin_budget_reached;
}

inline std::string levels(int n) { return fmt::format("{} {}", n, n == 1 ? "level" : "levels"); }

/// The sub-step `s` from `before` (t to t + k) when its contours change the topology (components
/// and holes or handles), checked against the same sub-step with thin cells two levels deeper:
/// the same topology there confirms the change (a part the law split off, joined, opened or made
/// vanish), and the deeper sub-step is kept; another says the coarser contours tore or joined a
/// part thinner than they resolve, and the rest of the step goes on at the deeper thin depth
/// (options', r.deepest_thin_depth, r.deeper_at), checked again the same way; time_loop starts
/// the next step from the run's own depth. At the deepest thin cells
/// (setting_range::thin_depth) the change is checked against two levels shallower instead. A
/// change two depths do not agree on, or thin cells at their budget (which split no deeper where
/// it ran out, and give the same contours at any depth), is unresolved: why, naming the thin
/// depths, the topologies they give and the place. Where deeper cells make holes or handles
/// that neither the step's start nor the depth in hand have (the gap narrowing to nothing where
/// parts meet), the step keeps the deepest depth from the one in hand down that adds no part,
/// hole or handle (r.shallower_at).
template <int dim>
Confirmed<dim> confirm_topology(typename LoopHooks<dim>::StepResult s, const ShapeOf<dim>& before,
                                double t, double k, const BasicVelocityLaw<dim>& law,
                                const RegionOf<dim>& domain,
                                typename LoopHooks<dim>::Options& options,
                                typename LoopHooks<dim>::Result& r) {
    using H = LoopHooks<dim>;
    int& thin = options.step.contour.thin_depth;
    const ShapeTopology was = shape_topology(before);
    ShapeTopology now = shape_topology(H::shape(s));
    // Why the change is not confirmed: `at`'s contours against those `depth` levels deep. Where
    // parts meet and the holes or handles rise, the edge between them narrows to nothing, which
    // thin cells resolve unevenly along it and pinch (two meshed spheres growing into each
    // other: hundreds of handles at every thin depth and K, none at thin depths 0 and 1).
    const auto unconfirmed = [&](const typename H::StepResult& at, int depth) {
        const bool pinched = now.holes > was.holes && now.components <= was.components;
        return fmt::format(
            "at t = {:.6g}: the step's contours made {} of {}{}, and thin cells {} deep{} do not "
            "confirm it: a part is thinner than they resolve; raise -K{}",
            t + k, describe(now, dim), describe(was, dim), finest_place(at), levels(depth),
            at_budget(at) ? ", at their budget of cells," : "",
            pinched ? fmt::format(", or, where parts meet, lower --thin-depth: thin cells can "
                                  "pinch the narrowing edge between them into {}",
                                  dim == 2 ? "holes" : "handles")
                    : "");
    };
    // Where parts meet, the gap between them narrows to nothing, and deeper thin cells make
    // holes or handles of it that come and go with the depth, more the deeper (two meshed
    // spheres growing into each other at K 4, meeting: 2, 0, 9, 19, 42, 47, 89, 221 and 413
    // handles at thin depths 0 to 8; two circles: a hole and a part at depth 8 where 6 merged
    // them), which no two depths confirm. Where deeper cells make holes or handles that neither
    // the step's start nor the depth in hand have, the step keeps the deepest depth, from the one
    // in hand (`at`, its sub-step `s`) down, whose contours have no more parts, holes or handles
    // than the start (r.shallower_at); the next step starts again from the run's own.
    const int entered = thin;
    // What going deeper recorded before this step tried (restored where it ends no deeper).
    const double deeper_at = r.deeper_at;
    const std::string deeper_why = r.deeper_why;
    const int deepest = r.deepest_thin_depth;
    bool tried = false;
    // s (whose topology is `now`) is the sub-step at the depth in hand; s_counted: it is in
    // r.g_evals as not kept. s is given back when no depth is kept.
    const auto shallower = [&](bool s_counted, const ShapeTopology& deeper_made,
                               int deeper_depth) -> std::optional<typename H::StepResult> {
        if (tried) return std::nullopt;
        tried = true;
        const int at = thin;
        const std::string place = finest_place(s);
        for (int d = at; d >= 0; --d) {
            typename H::Options o = options;
            o.step.contour.thin_depth = d;
            typename H::StepResult here =
                d == at ? std::move(s)
                        : step_in_growing_domain<dim>(before, t, k, law, domain, o, r);
            const ShapeTopology got = d == at ? now : shape_topology(H::shape(here));
            if (got.components >= 1 && got.components <= was.components && got.holes <= was.holes &&
                !at_budget(here)) {
                if (std::isnan(r.shallower_at)) {
                    r.shallower_at = t;
                    r.shallower_why = fmt::format(
                        "at t = {:.6g} thin cells {} deep made {} of {}{}, and {} deep {}", t + k,
                        levels(deeper_depth), describe(deeper_made, dim), describe(was, dim), place,
                        levels(d), describe(got, dim));
                }
                if (d == at && s_counted) r.g_evals -= here.stats.g_evals();
                thin = d;
                r.shallowest_thin_depth = std::min(r.shallowest_thin_depth, d);
                ++r.shallower_substeps;
                if (d <= entered) {
                    r.deeper_at = deeper_at;
                    r.deeper_why = deeper_why;
                    r.deepest_thin_depth = deepest;
                }
                return here;
            }
            if (d == at)
                s = std::move(here);
            else
                r.g_evals += here.stats.g_evals();  // not kept
        }
        return std::nullopt;
    };
    while (now != was) {
        if (thin >= setting_range::thin_depth.hi) {
            typename H::Options o = options;
            o.step.contour.thin_depth = thin - 2;
            typename H::StepResult coarser =
                step_in_growing_domain<dim>(before, t, k, law, domain, o, r);
            r.g_evals += coarser.stats.g_evals();  // a confirmation, not kept
            if (shape_topology(H::shape(coarser)) == now && !at_budget(s))
                return {std::move(s), std::nullopt};
            if (const int at = thin; now.holes > was.holes) {
                if (auto kept = shallower(false, now, thin)) {
                    if (thin < at) r.g_evals += s.stats.g_evals();  // not kept
                    return {std::move(*kept), std::nullopt};
                }
            }
            std::string why = unconfirmed(s, thin - 2);
            return {std::move(s), std::move(why)};
        }
        typename H::Options o = options;
        o.step.contour.thin_depth = std::min(thin + 2, setting_range::thin_depth.hi);
        typename H::StepResult deeper =
            step_in_growing_domain<dim>(before, t, k, law, domain, o, r);
        const ShapeTopology there = shape_topology(H::shape(deeper));
        r.g_evals += s.stats.g_evals();  // the coarser sub-step, not kept
        if (there == now) {
            if (at_budget(deeper)) {
                std::string why = unconfirmed(deeper, o.step.contour.thin_depth);
                return {std::move(deeper), std::move(why)};
            }
            return {std::move(deeper), std::nullopt};
        }
        if (there.holes > std::max(now.holes, was.holes)) {
            // Deeper cells make holes or handles that neither the start nor these have.
            if (auto kept = shallower(true, there, o.step.contour.thin_depth)) {
                r.g_evals += deeper.stats.g_evals();  // not kept
                return {std::move(*kept), std::nullopt};
            }
        }
        // The coarser contours tore or joined what the deeper keep: the step goes on deeper.
        if (std::isnan(r.deeper_at)) {
            r.deeper_at = t;
            r.deeper_why = fmt::format(
                "at t = {:.6g} thin cells {} deep made {} of {}{}, and {} deep {}", t + k,
                levels(thin), describe(now, dim), describe(was, dim), finest_place(deeper),
                levels(o.step.contour.thin_depth), describe(there, dim));
        }
        thin = o.step.contour.thin_depth;
        r.deepest_thin_depth = std::max(r.deepest_thin_depth, thin);
        s = std::move(deeper);
        now = there;
    }
    return {std::move(s), std::nullopt};
}

/// What else to name when a step of a normal law whose speed varies (normal_speed_varies) breaks
/// its law in every split while thin cells are on: the loops its step leaves in G at a
/// non-convex Wulff shape's corners are not mended by more steps or a deeper K (the defaults
/// campaign's case 45 at thin depth 6: unstable at N = 40, 80 and at K = 6; ok at thin depth 2).
template <int dim>
std::string thin_cells_hint(const BasicVelocityLaw<dim>& law, int thin_depth) {
    if (thin_depth == 0 || !normal_speed_varies(law)) return {};
    return ", or lower --thin-depth (thin cells resolve loops of G smaller than a cell, as the "
           "corners of a speed that depends on the normal leave)";
}

/// The step from Γ(t) (r's) to t_next: whole, or when it breaks the law's invariants (guards)
/// in sub-steps, each one that breaks them taken again in halves, down to 1/2^halvings of the
/// step. A sub-step that fails (NumericalFailure: a contour that leaves a fixed domain, say) is
/// halved the same way. The hooks check each sub-step (LoopHooks::record) and the run's budget
/// after the step (LoopHooks::run_budget), and add what the kept sub-steps did to r
/// (LoopHooks::commit).
///
/// With the guards and thin cells (thin_depth > 0), a sub-step that changes the topology is
/// confirmed by deeper thin cells first (confirm_topology); one the deepest do not confirm is
/// split as a step that breaks an invariant, and a break of the law's own invariants, which
/// names the cause better, is the one reported. With no thin cells (the paper's uniform trees), a
/// part split off thinner than the finest cell is noted (r.thin_split).
///
/// Throws Unstable when a sub-step of 1/2^halvings breaks the invariants or the run leaves its
/// budget, and the NumericalFailure of a sub-step that fine.
template <int dim>
typename LoopHooks<dim>::StepResult guarded_step(typename LoopHooks<dim>::Result& r, double t_next,
                                                 const LoopHooks<dim>& hooks,
                                                 const BasicVelocityLaw<dim>& law,
                                                 const RegionOf<dim>& domain,
                                                 typename LoopHooks<dim>::Options& options) {
    using H = LoopHooks<dim>;
    const int halvings = options.guards ? options.max_substep_halvings : 0;
    const int& thin = options.step.contour.thin_depth;
    const typename H::Start start = hooks.start(H::shape(r));
    std::string violation, torn;  // the law's last break; a change the contours cannot confirm
    // The last pass beyond only a share of a budget (BudgetBreach::share), kept in case a finer
    // pass does no better or breaks.
    struct Pass {
        typename H::StepResult out;
        typename H::Attempt attempt;
        int taken = 0;
        double excess = 0.0;
    };
    std::optional<Pass> best;
    const auto keep = [&](typename H::StepResult out, const typename H::Attempt& attempt,
                          int taken) {
        hooks.commit(attempt, r);
        if (taken > 1) {
            ++r.split_steps;
            r.most_substeps = std::max(r.most_substeps, taken);
        }
        return out;
    };
    const auto keep_best = [&] { return keep(std::move(best->out), best->attempt, best->taken); };
    // Each pass walks the step in sub-steps of (t_next − r.t)/2^level, level from `least` up to
    // `halvings`: a sub-step that fails is taken again in halves from where it started, and the
    // rest of the step at the level that succeeded (growing back to longer sub-steps within the
    // step lets a corner's first rounding roughen the curve unseen). Where the whole step broke
    // the run's budget, a pass starts over one level finer than the finest the last one took.
    for (int least = 0, finest = 0; least <= halvings; least = finest + 1) {
        typename H::StepResult out{H::shape(r), {}};
        typename H::Attempt attempt{start};
        double t = r.t;
        int level = least, taken = 0;
        finest = least;
        std::int64_t at = 0;  // t = r.t + (t_next − r.t) at / 2^level
        while (!H::shape(out).empty()) {
            const std::int64_t parts = std::int64_t{1} << level;
            const double t_to = at + 1 == parts
                                    ? t_next
                                    : r.t + (t_next - r.t) * static_cast<double>(at + 1) /
                                                static_cast<double>(parts);
            const double k = H::substep_length(r.t, t_next, static_cast<int>(parts), t, t_to);
            typename H::StepResult s;
            std::optional<std::string> unresolved;
            bool failed = false;
            try {
                s = step_in_growing_domain<dim>(H::shape(out), t, k, law, domain, options, r);
                if (options.guards && thin > 0) {
                    Confirmed<dim> c = confirm_topology<dim>(std::move(s), H::shape(out), t, k, law,
                                                             domain, options, r);
                    s = std::move(c.step);
                    unresolved = std::move(c.unresolved);
                }
                check_extent<NumericalFailure>(
                    law, H::shape(s), [&](const std::string& region, std::size_t, const auto& p) {
                        return fmt::format(
                            "at t = {} {} left the region where velocity '{}' is known, {}, at "
                            "{}: give the velocity on a larger grid, or end the run earlier "
                            "(t-end)",
                            t_to, H::noun, law.name(), region, point_text(p));
                    });
            } catch (const LimitExceeded&) {
                throw;  // a setting beyond a limit: smaller steps would not help
            } catch (const NumericalFailure&) {
                // A step too large for the features may fail where smaller ones do not.
                if (level == halvings) throw;
                failed = true;
            }
            if (!failed && thin == 0 && std::isnan(r.thin_split.at)) {
                // No thin cells asked: the paper's uniform trees, whose tears are noted.
                const double cell = std::ldexp(domain.width(), -options.step.contour.depth);
                if (const auto part = thinnest_new_part<dim>(H::shape(out), H::shape(s));
                    part && part->thickness < cell) {
                    r.thin_split = {t_to, part->thickness, cell, {}};
                    for (int c = 0; c < dim; ++c) r.thin_split.near.push_back(part->where[c]);
                }
            }
            // A law's own invariant names the break better (and smaller steps may keep it).
            const typename H::Attempt before = attempt;  // what a failed sub-step leaves
            if (!failed && unresolved && law.invariants().rigid) {
                // A rigid motion keeps the topology over any step: contours that no thin depth
                // resolves are the shape's, and every shorter sub-step would meet them again.
                throw Unstable{*unresolved +
                               "; a rigid motion keeps the topology at any step, so shorter steps "
                               "cannot mend it"};
            }
            if (!failed) {
                if (auto v = hooks.record(attempt, H::shape(out), s, t, k, r)) {
                    violation = std::move(*v);
                    failed = true;
                } else if (unresolved) {
                    if (violation.empty()) torn = std::move(*unresolved);
                    failed = true;
                }
            }
            if (failed) {
                attempt = before;
                if (level == halvings) {
                    if (best) return keep_best();
                    throw Unstable{hooks.unstable_after_splits(violation.empty() ? torn : violation,
                                                               1 << halvings, r.t) +
                                   thin_cells_hint(law, thin)};
                }
                finest = std::max(finest, ++level);
                at *= 2;
                continue;
            }
            out = std::move(s);
            t = t_to;
            ++taken;
            if (++at == parts) break;
        }
        std::optional<BudgetBreach> over_budget =
            hooks.run_budget(attempt, H::shape(out), t_next, r);
        if (over_budget && over_budget->share()) {
            // Beyond its share only: finer while each pass takes the excess down by a quarter
            // (a lag of the time step halves), else the better of the last two is kept.
            const double excess = over_budget->excess;
            over_budget.reset();
            if (!best || excess < 0.75 * best->excess) {
                if (finest < halvings) {
                    best = Pass{std::move(out), attempt, taken, excess};
                    continue;
                }
            } else if (best->excess < excess) {
                return keep_best();
            }
        }
        if (over_budget && !options.guards) {
            note_broken(r, std::move(over_budget->message));
            over_budget.reset();
        }
        // A run beyond its budget ends with the interface before the step that took it there,
        // which its history holds last; where smaller steps may keep it, the step is taken
        // again in finer sub-steps first, as one that breaks an invariant. A finer pass after
        // one beyond only a share falls back to that one.
        if (over_budget) {
            if (best) return keep_best();
            if (over_budget->split && finest < halvings) {
                violation = std::move(over_budget->message);
                continue;
            }
            throw Unstable{std::move(over_budget->message)};
        }
        return keep(std::move(out), attempt, taken);
    }
    if (best) return keep_best();
    throw Unstable{
        hooks.unstable_after_splits(violation.empty() ? torn : violation, 1 << halvings, r.t) +
        thin_cells_hint(law, thin)};
}

/// Throws InvalidInput unless `from` is a state a run with `options` passes through.
template <int dim>
void check_resume(const typename LoopHooks<dim>::Result& from, const BasicVelocityLaw<dim>& law,
                  const typename LoopHooks<dim>::Options& options) {
    using H = LoopHooks<dim>;
    check_run_options(options);
    H::check_start(from);
    check_extent<InvalidInput>(
        law, H::shape(from), [&](const std::string& region, std::size_t i, const auto& p) {
            return fmt::format(
                "the initial {} {} the region where velocity '{}' is known, {}: vertex {} at {}",
                H::shape_name, H::leave, law.name(), region, i, point_text(p));
        });
    // A bounded speed over the run's time gives how far the interface may move: beyond the
    // coordinate limit, its arithmetic would overflow (and the interface vanish from sight).
    if (const std::optional<double> s = law.speed_bound()) {
        if (!std::isfinite(*s)) {
            throw InvalidInput(fmt::format("velocity '{}' has a speed of {:g}, not a finite number",
                                           law.name(), *s));
        }
        const double reach = *s * (options.t_end - options.t_start);
        if (!(reach <= tolerance::max_coordinate)) {
            throw InvalidInput(fmt::format(
                "velocity '{}' at speed up to {:g} moves the {} by up to {:g} from t = {} to {}, "
                "beyond the coordinate limit ±{:g}, where the arithmetic overflows: lower the "
                "speed or t-end",
                law.name(), *s, H::shape_name, reach, options.t_start, options.t_end,
                tolerance::max_coordinate));
        }
    }
    if (from.steps_done < 0 || from.steps_done >= options.steps) {
        throw InvalidInput(fmt::format("cannot resume after step {} of a run of {} steps",
                                       from.steps_done, options.steps));
    }
    if (from.t != time_after(options, from.steps_done)) {
        throw InvalidInput(fmt::format("cannot resume: t = {} is not the time after step {} ({})",
                                       from.t, from.steps_done,
                                       time_after(options, from.steps_done)));
    }
}

/// Steps from.steps_done + 1 .. N from `from`, with the options `given` (their thin cells at
/// least from.thin_depth), its counters and clocks carried on: resume() of
/// either dimension. Failures inside a step end the run with status error, a step or a run that
/// breaks what the law keeps with status unstable, an empty interface with vanished, an observer
/// that returns false before the last step with interrupted.
template <int dim>
typename LoopHooks<dim>::Result time_loop(const typename LoopHooks<dim>::Result& from,
                                          const BasicVelocityLaw<dim>& law,
                                          const RegionOf<dim>& domain,
                                          const typename LoopHooks<dim>::Options& given,
                                          const typename LoopHooks<dim>::Observer& observer) {
    using H = LoopHooks<dim>;
    check_resume<dim>(from, law, given);
    // The thin cells the start or a step before needed (RunTotals::thin_depth), also on a
    // resume; guarded_step deepens them where a step needs more.
    typename H::Options options = given;
    int& thin = options.step.contour.thin_depth;
    thin = std::max(thin, from.thin_depth);
    const int asked_thin = thin;
    const H hooks(law, domain, options);
    typename H::Result r = from;
    r.thin_depth = thin;
    r.status = RunStatus::ok;
    r.message.clear();
    const double wall_before = from.wall_s, cpu_before = from.cpu_s;
    const auto wall_start = std::chrono::steady_clock::now();
    const std::int64_t cpu_start = process_cpu_ns();
    auto clocks = [&] {
        r.wall_s =
            wall_before +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        r.cpu_s = cpu_before + seconds(process_cpu_ns() - cpu_start);
    };
    for (int n = from.steps_done + 1; n <= options.steps; ++n) {
        const double t_next = time_after(options, n);
        typename H::StepResult step;
        const std::int64_t step_cpu_start = process_cpu_ns();
        try {
            // Each step starts from the thin cells the run asked (or its start needed); the
            // deeper ones a step took for a part thinner than those resolve, and the shallower
            // ones it kept where parts meet, are that step's.
            thin = asked_thin;
            step = guarded_step<dim>(r, t_next, hooks, law, domain, options);
            if (thin > asked_thin) ++r.deeper_steps;
        } catch (const NumericalFailure& e) {
            r.status = RunStatus::error;
            r.message = H::step_failed(n, r.t, e.what());
            break;
        } catch (const Unstable& e) {
            r.status = RunStatus::unstable;
            r.message = H::at_step(n, r.t, e.message);
            break;
        } catch (const StopRequested&) {
            // Stopped within the step (slc/core/stop.hpp): the run holds the last whole one.
            r.status = RunStatus::interrupted;
            break;
        }
        const double step_cpu_s = seconds(process_cpu_ns() - step_cpu_start);
        H::shape(r) = std::move(H::shape(step));
        r.t = t_next;
        r.steps_done = n;
        clocks();
        const bool vanished = H::shape(r).empty();
        const bool go_on =
            !observer || observer(typename H::Report{n, options.steps, r.t, &H::shape(r),
                                                     &step.stats, r.wall_s, step_cpu_s, &r});
        if (vanished) {
            r.status = RunStatus::vanished;
            r.message = r.broken;
            break;
        }
        if (options.stop_components > 0 && n < options.steps) {
            const std::size_t left = H::components(H::shape(r));
            if (left <= options.stop_components) {
                r.message = fmt::format("stopped at t = {:.6g}: {} components left (asked for {})",
                                        r.t, left, options.stop_components);
                break;
            }
        }
        if (!go_on && n < options.steps) {
            r.status = RunStatus::interrupted;
            break;
        }
        if (n == options.steps && !r.broken.empty()) {
            r.status = RunStatus::broken;
            r.message = r.broken;
        }
    }
    clocks();
    return r;
}

}  // namespace slc::detail
