// The time loop of surfaces: steps, sub-steps the guards ask for, vanishing, failures, clocks.
#include "slc/evolve/surface_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/tree/tetrahedralization.hpp"
#include "slc/velocity/surface_laws.hpp"

namespace slc {
namespace {

double process_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void check(const SurfaceRunOptions& o) {
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

/// When a flow field carries a vertex of s out of the domain within the step (its forward Euler
/// image, x + k u(t, x), outside): the message of LeftDomain, naming the first such vertex. An
/// empty contour from such a step is a surface that left the domain, not one that vanished.
std::optional<std::string> carried_out(const Surface& s, double t, double k,
                                       const SurfaceVelocityLaw& law, const Box3& domain) {
    if (!law.is_field()) return std::nullopt;
    std::vector<Vec3> u(s.vertices.size());
    law.sample(t, s.vertices, u);
    for (std::size_t i = 0; i < u.size(); ++i) {
        const Vec3 x = s.vertices[i], y = x + k * u[i];
        if (domain.contains(y)) continue;
        return fmt::format(
            "the flow carries the surface out of the domain [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] "
            "x [{:.6g}, {:.6g}] within a step, ({:.6g}, {:.6g}, {:.6g}) to near ({:.6g}, {:.6g}, "
            "{:.6g}): give a domain that holds its whole path (--domain, --box), or take more "
            "steps (-N)",
            domain.lo.x, domain.hi.x, domain.lo.y, domain.hi.y, domain.lo.z, domain.hi.z, x.x, x.y,
            x.z, y.x, y.y, y.z);
    }
    return std::nullopt;
}

/// One step in the domain that holds the surface: doubled the fewest times that keep its
/// bounding box an eighth of the doubled width from the edge, then once more each time the
/// contour reaches the edge (SurfaceRunOptions::max_domain_doublings), K a level deeper per
/// doubling. Records the doublings in `r`.
SurfaceStepResult advance_in_growing_domain(const Surface& s, double t, double k,
                                            const SurfaceVelocityLaw& law, const Box3& domain,
                                            const SurfaceRunOptions& options, SurfaceRunResult& r) {
    const int most = std::min(options.max_domain_doublings,
                              max_tetrahedralized_depth - options.step.contour.depth);
    int j = 0;
    if (most > 0) {
        const Box3 b = bounding_box(s);
        for (; j < most; ++j) {
            const Box3 d = doubled_domain(domain, j);
            if (d.inflated(-0.125 * d.width()).contains(b)) break;
        }
    }
    for (;; ++j) {
        SurfaceStepOptions o = options.step;
        o.contour.depth += j;
        try {
            SurfaceStepResult step = advance(s, t, k, law, doubled_domain(domain, j), o);
            if (step.surface.empty()) {
                if (const auto out = carried_out(s, t, k, law, doubled_domain(domain, j)))
                    throw LeftDomain(*out);
            }
            if (j > r.domain_doublings) {
                if (r.domain_doublings == 0) r.domain_grown_at = t;
                r.domain_doublings = j;
            }
            return step;
        } catch (const LeftDomain&) {
            if (j >= most) throw;
        }
    }
}

/// The time after n of the N steps, from the step count so that the last step ends at t_end.
double time_after(const SurfaceRunOptions& o, int n) {
    return n == o.steps ? o.t_end : o.t_start + n * ((o.t_end - o.t_start) / o.steps);
}

}  // namespace

Surface surface_as_read(const Surface& s, const Box3& domain, const SurfaceRunOptions& options) {
    // A flow field at rest: G(x) = F(x), so the step's contour is the surface's own.
    const SurfaceTranslation rest({0.0, 0.0, 0.0});
    Surface read = advance(s, options.t_start, 1.0, rest, domain, options.step).surface;
    if (read.empty() && !s.empty()) {
        const Box3 b = bounding_box(s);
        throw InvalidInput(fmt::format(
            "the surface, {:.3g} across, is too small for the contours to see: the finest cell "
            "at K = {} in the domain {:.3g} wide is {:.3g}; raise K (-K) or give a smaller "
            "domain",
            std::max({b.extent(0), b.extent(1), b.extent(2)}), options.step.contour.depth,
            domain.width(), std::ldexp(domain.width(), -options.step.contour.depth)));
    }
    return read;
}

Box3 doubled_domain(const Box3& domain, int times) {
    if (times == 0) return domain;
    return Box3::cube(domain.center(), std::ldexp(0.5 * domain.width(), times));
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

double finest_cell(const Box3& domain, const SurfaceContourOptions& contour) {
    return std::ldexp(domain.width(), -(contour.depth + contour.thin_depth));
}

std::optional<double> thinnest_new_component(const Surface& before, const Surface& after) {
    const std::size_t old_count = component_count(before);
    const std::vector<std::uint32_t> label = component_labels(after);
    const std::size_t count =
        label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + std::size_t{1};
    if (count <= old_count) return std::nullopt;
    // Each component's volume (the divergence theorem, from any origin: its own first vertex)
    // and area.
    std::vector<double> v(count, 0.0), a(count, 0.0);
    std::vector<Vec3> origin(count);
    std::vector<std::uint8_t> seen(count, 0);
    for (std::size_t t = 0; t < after.size(); ++t) {
        const std::uint32_t c = label[t];
        const Triangle3 tri = after.triangle(t);
        if (!seen[c]) origin[c] = tri.a, seen[c] = 1;
        const Vec3 p = tri.a - origin[c], q = tri.b - origin[c], r = tri.c - origin[c];
        v[c] += dot(p, cross(q, r)) / 6.0;
        a[c] += 0.5 * norm(cross(tri.b - tri.a, tri.c - tri.a));
    }
    // The new components are the thinnest ones: a split makes parts of a whole.
    std::vector<double> thickness(count);
    for (std::size_t c = 0; c < count; ++c) thickness[c] = a[c] > 0.0 ? 3.0 * v[c] / a[c] : 0.0;
    std::sort(thickness.begin(), thickness.end());
    return thickness[count - old_count - 1];
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
    check(options);
    if (from.surface.empty()) throw InvalidInput("the surface to resume has no triangles");
    if (from.steps_done < 0 || from.steps_done >= options.steps) {
        throw InvalidInput(fmt::format("cannot resume after step {} of a run of {} steps",
                                       from.steps_done, options.steps));
    }
    if (from.t != time_after(options, from.steps_done)) {
        throw InvalidInput(fmt::format("cannot resume: t = {} is not the time after step {} ({})",
                                       from.t, from.steps_done,
                                       time_after(options, from.steps_done)));
    }
    SurfaceRunResult r = from;
    r.status = RunStatus::ok;
    r.message.clear();
    // What a step broke: with the guards on, the end of the run; off, noted the first time.
    const auto stop_or_note = [&](std::string why) {
        if (options.guards) {
            r.status = RunStatus::unstable;
            r.message = std::move(why);
            return true;
        }
        if (r.broken.empty()) r.broken = std::move(why);
        return false;
    };
    const Invariants invariants = law.invariants();
    const double eps = options.step.contour.resolved_eps();
    const double cell = finest_cell(domain, options.step.contour);
    const bool until_converged =
        options.step.contour.refine_passes == SurfaceContourOptions::until_converged;
    const double volume0 = from.volume_initial;
    const double wall_before = from.wall_s, cpu_before = from.cpu_s;
    const auto wall_start = std::chrono::steady_clock::now();
    const double cpu_start = process_cpu_s();
    auto clocks = [&] {
        r.wall_s =
            wall_before +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        r.cpu_s = cpu_before + process_cpu_s() - cpu_start;
    };
    for (int n = from.steps_done + 1; n <= options.steps; ++n) {
        const double t0 = time_after(options, n - 1), t1 = time_after(options, n);
        SurfaceStepStats stats;
        try {
            // The step, in 1, 2, 4, ... sub-steps until it keeps what the law keeps.
            for (int halvings = 0;; ++halvings) {
                const int pieces = 1 << halvings;
                const double k = (t1 - t0) / pieces;
                Surface s = r.surface;
                std::optional<std::string> broken;
                double corrected = 0.0;
                bool unconverged = false;
                double residual = 0.0;
                double thin_at = std::numeric_limits<double>::quiet_NaN(), thin_thickness = 0.0;
                for (int j = 0; j < pieces && !s.empty(); ++j) {
                    SurfaceStepResult step =
                        advance_in_growing_domain(s, t0 + j * k, k, law, domain, options, r);
                    r.g_evals += step.stats.g_evals();
                    corrected += step.stats.volume_correction;
                    if (until_converged && !step.surface.empty() &&
                        !step.stats.corrector.converged) {
                        unconverged = true;
                        residual = std::max(residual, step.stats.corrector.residual);
                    }
                    stats = step.stats;
                    if (const auto thin = thinnest_new_component(s, step.surface);
                        thin && *thin < cell && std::isnan(thin_at)) {
                        thin_at = t0 + (j + 1) * k;
                        thin_thickness = *thin;
                    }
                    if (auto v = surface_invariant_violation(invariants, s, step.surface, k, eps)) {
                        if (options.guards) {
                            broken = std::move(v);
                            break;
                        }
                        // Without guards the step is kept whole: noted, not split.
                        stop_or_note(
                            fmt::format("at t = {:.6g}: {}; refine the time step (-N) or the "
                                        "contours (-K, --eps)",
                                        t0 + j * k, *v));
                    }
                    s = std::move(step.surface);
                }
                if (!broken) {
                    if (pieces > 1) {
                        ++r.split_steps;
                        r.most_substeps = std::max(r.most_substeps, pieces);
                    }
                    r.surface = std::move(s);
                    r.volume_corrected += corrected;
                    if (unconverged) {
                        ++r.unconverged_steps;
                        r.largest_residual = std::max(r.largest_residual, residual);
                    }
                    if (std::isnan(r.thin_split_at) && !std::isnan(thin_at)) {
                        r.thin_split_at = thin_at;
                        r.thin_split_thickness = thin_thickness;
                    }
                    break;
                }
                if (halvings == options.max_substep_halvings) {
                    r.status = RunStatus::unstable;  // (only the guards split a step)
                    r.message = fmt::format(
                        "at t = {:.6g}: {} (also in {} sub-steps); refine the time step (-N) or "
                        "the contours (-K, --eps)",
                        t0, *broken, pieces);
                    clocks();
                    return r;
                }
            }
        } catch (const NumericalFailure& e) {
            r.status = RunStatus::error;
            r.message = fmt::format("at t = {:.6g}: {}", t0, e.what());
            clocks();
            return r;
        }
        r.t = t1;
        r.steps_done = n;
        clocks();
        if (invariants.keeps_area && !r.surface.empty()) {
            const double drift = volume(r.surface) / volume0 - 1.0;
            if (std::abs(drift) > options.volume_drift &&
                stop_or_note(fmt::format(
                    "at t = {:.6g}: the volume drifted by {:.3g}% since the start under a law that "
                    "keeps it (more than {:.3g}%); take more steps (-N), refine the contours "
                    "(-K, --eps) or allow more drift (--volume-drift)",
                    t1, 100.0 * drift, 100.0 * options.volume_drift)))
                return r;
        }
        if (invariants.shortens && !r.surface.empty()) {
            if (const auto growth =
                    growth_above_least(r.least_area, area(r.surface), t1, options.area_growth,
                                       20.0 * eps * std::sqrt(r.least_area.value));
                growth &&
                stop_or_note(fmt::format(
                    "at t = {:.6g}: the area has grown by {:.3g}% since t = {:.6g} under a law "
                    "that shrinks it, more than the run's {:g}%: the steps roughen the surface; "
                    "take more steps (-N) or refine the contours (-K, --eps)",
                    t1, 100.0 * *growth, r.least_area.t, 100.0 * options.area_growth)))
                return r;
        }
        if (r.surface.empty()) {
            r.status = RunStatus::vanished;
            r.message = r.broken;
            return r;
        }
        if (observer) {
            const SurfaceStepReport report{n, options.steps, r.t, &r.surface, &stats, &r};
            if (!observer(report) && n < options.steps) {
                r.status = RunStatus::interrupted;
                return r;
            }
        }
    }
    if (!r.broken.empty()) {
        r.status = RunStatus::broken;
        r.message = r.broken;
    }
    return r;
}

}  // namespace slc
