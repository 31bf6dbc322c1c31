// The predictor–corrector step (paper §1.2 Eqs. 4, 5; §4.3 "Semi-Lagrangian evaluation"),
// written once for curves (step.cpp) and surfaces (surface_step.cpp), internal to evolve. Each of
// those files keeps what differs: its Level (the distance tree of Γ at one time, the vertex
// velocities and their extension W, arcs or patches), the checks of its options, and how its
// enclosed measure is kept.
//
// A Level answers, at a point x:
//   distance(x)                    F: the signed distance to Γ (to its arcs or patches if asked)
//   chord_distance(x)              the exact distance to its segments or triangles
//   velocity(x)                    W(x), the extension of the vertex velocities
//   closest_point_and_velocity(x)  the closest point of the segments or triangles, and W(x)
//   distances_and_normals, normal_speeds   what a normal law's step needs (step_common.hpp)
// and of Γ: max_speed() (max|W|), normal_speed_bound() (a normal law's max|V|, if known),
// max_bulge() (the most distance() differs from chord_distance()), add_normal_speed(s).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "slc/contour/contour.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/stop.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/evolve/step.hpp"
#include "slc/evolve/surface_step.hpp"
#include "step_common.hpp"

namespace slc::detail {

/// The contour of the dimension, with the step's bounds on G: contour() in the plane,
/// contour_surface() in space.
inline ContourResult contour_of(BatchFunctionRef g, const Box& domain, const ContourOptions& o,
                                std::optional<BatchBoundsRef> bounds) {
    check_stop();
    return bounds ? contour(g, domain, o, *bounds) : contour(g, domain, o);
}
inline SurfaceContour contour_of(SpaceFunctionRef g, const Box3& domain,
                                 const SurfaceContourOptions& o,
                                 std::optional<SpaceBoundsRef> bounds) {
    check_stop();
    return bounds ? contour_surface(g, domain, o, *bounds) : contour_surface(g, domain, o);
}

/// The interface a contour or a step produced.
inline Interface& shape_of(ContourResult& r) { return r.curves; }
inline Surface& shape_of(SurfaceContour& r) { return r.surface; }
inline Interface& shape_of(StepResult& r) { return r.curves; }
inline Surface& shape_of(SurfaceStepResult& r) { return r.surface; }
/// Its vertices.
inline std::span<const Vec2> vertices_of(const Interface& curves) { return curves.points(); }
inline std::span<const Vec3> vertices_of(const Surface& surface) { return surface.vertices; }
/// Whether it has nothing left.
inline bool vanished(const Interface& curves) { return curves.empty(); }
inline bool vanished(const Surface& surface) { return surface.empty(); }

/// The bounds F(x) ± reach on G, one distance query each: G moves its foot at most `reach`
/// from x, or changes F by at most that much.
template <class Point, class Distance>
auto distance_bounds(Distance distance, double reach) {
    return pointwise<Point>(
        [distance, reach](Point x) {
            const double f = distance(x);
            return Interval{f - reach, f + reach};
        },
        expensive_grain);
}

/// A normal law's step with the distance field's normal N (Extension::direct). F is a distance,
/// so moving x by a along N changes it by a while x stays on its normal line: the
/// semi-Lagrangian value F(x − k V N) is F(x) − k V. Written so, it also holds where the foot
/// would cross the medial axis (through a thin part, or a corner's tip when Γ grows): the level
/// set F = k V is then the exact offset, and the viscosity solution's corners follow. The
/// trapezoidal rule averages V at the foot at t and at x at t + k, the predicted interface's
/// normal at x standing in for the normal there. With |V| ≤ S, G is within kS of F, which is
/// within b of a distance: |G(x) − G(y)| ≤ |x − y| + 2 (kS + b), and F ± (kS + b) bound G.
/// make_level(shape, t) makes a Level at time t.
template <class Result, class Shape, class Region, class ContourOptions, class MakeLevel>
Result advance_normal_law(const Shape& shape, double t, double k, const Region& domain,
                          const ContourOptions& contour_options, MakeLevel make_level) {
    using Point = typename std::remove_cvref_t<decltype(vertices_of(shape))>::value_type;
    Result result;
    const auto now = make_level(shape, t);
    // The contour, with the slack and bounds of a reach when the law's speed is bounded.
    const auto contour_within = [&](auto g, std::optional<double> reach) {
        const auto f = [&now](Point x) { return now.distance(x); };
        if (!reach) return contour_of(g, domain, contour_options, std::nullopt);
        ContourOptions within = contour_options;
        within.distance_slack = 2.0 * *reach;
        return contour_of(g, domain, within, distance_bounds<Point>(f, *reach));
    };
    const std::optional<double> s_now = now.normal_speed_bound();
    const auto predictor = [&](std::span<const Point> xs, std::span<double> g) {
        normal_predictor(now, k, xs, g);
    };
    auto predicted = contour_within(
        predictor, s_now ? std::optional(k * *s_now + now.max_bulge()) : std::nullopt);
    if (now.constant_speed()) {
        // The corrector's G would be the predictor's to the last bit (constant_speed()): the
        // predicted contour is the step's, its statistics the final contour's, as for a flow.
        result.stats.corrector = predicted.stats;
        shape_of(result) = std::move(shape_of(predicted));
        return result;
    }
    result.stats.predictor = predicted.stats;
    if (vanished(shape_of(predicted))) return result;

    const auto next = make_level(shape_of(predicted), t + k);
    const std::optional<double> s_next = next.normal_speed_bound();
    const auto corrector = [&](std::span<const Point> xs, std::span<double> g) {
        normal_corrector(now, next, k, xs, g);
    };
    auto corrected = contour_within(
        corrector, s_now && s_next ? std::optional(0.5 * k * (*s_now + *s_next) +
                                                   std::max(now.max_bulge(), next.max_bulge()))
                                   : std::nullopt);
    result.stats.corrector = corrected.stats;
    shape_of(result) = std::move(shape_of(corrected));
    return result;
}

/// A flow field's step (Extension::direct): the field is known everywhere, so the foot of each
/// characteristic needs no predicted interface: G(x) = F(departure point of x; Γ(t)), one
/// contour, the feet traced to a tenth of ε. G is evaluated a batch at a time, so that the law
/// is sampled once per Runge–Kutta stage of each batch.
template <class Result, class Shape, class Law, class Region, class ContourOptions, class Level>
Result advance_flow(const Shape& shape, double t, double k, const Law& law, const Region& domain,
                    const ContourOptions& contour_options, const Level& now) {
    using Point = typename std::remove_cvref_t<decltype(vertices_of(shape))>::value_type;
    Result result;
    const int substeps = departure_substeps(law, t, k, vertices_of(shape),
                                            departure_tolerance * contour_options.resolved_eps());
    const auto g = [&](std::span<const Point> xs, std::span<double> values) {
        const std::vector<Point> feet = runge_kutta_feet(law, t, k, xs, substeps);
        parallel_for(
            xs.size(), [&](std::size_t i) { values[i] = now.distance(feet[i]); }, expensive_grain);
    };
    auto traced = contour_of(g, domain, contour_options, std::nullopt);
    result.stats.corrector = traced.stats;
    shape_of(result) = std::move(shape_of(traced));
    return result;
}

/// The measure a nonlocal law's step keeps, relative, and the contours of the corrector that
/// adjust its mean at most (the first shift and three secant steps): with one shift alone the
/// spiral of Fig. 18 drifted by 1e−4 to 4e−4 in steps where its corners round off, the bubbles
/// of Fig. 19 where they merge (docs/notes/area-preserving.md).
inline constexpr double mean_tolerance = 1e-8;
inline constexpr int mean_rounds = 4;

/// The step with an extension W of the vertex velocities (nearest-point or Whitney).
///
/// Predictor (Eq. 4, with our sign): G̃(x) = F(x − k W(x); Γ(t)). F is 1-Lipschitz, so G̃(x)
/// lies within k|W(x)| of F(x), and |G̃(x) − G̃(y)| ≤ |x − y| + 2d with d = k max|W|; and |G̃(x)|
/// is at most the foot's distance to the point of Γ(t) nearest x. One distance query bounds G̃
/// where G̃ itself takes two. With arcs or patches, F is the segments' or triangles' distance
/// plus a bulge of at most b, which adds b to the foot's move and to that distance.
///
/// Corrector (Eq. 5): the trapezoidal rule along the characteristic through x. Its foot moves at
/// most d = k/2 (max|W(t)| + max|W(t + k)|) from x; the bounds F(x) ± d need one query where G
/// needs four.
///
/// A nonlocal law's mean (one that keeps the enclosed measure) is the Lagrange multiplier of
/// that measure. Taken over Γ(t), it makes the speeds integrate to zero there, not over the
/// interface the step produces, which is off by O(k²) a step where the curvature is resolved and
/// by far more where it is not (a spiral's arms and corners): the mean is moved by the measure
/// the corrector's interface gained over k times its boundary measure, both levels alike, and
/// the corrector contoured again; then, unless the step's measure is `restored` after it (the
/// area or volume correction), by secant steps, each a contour, until the measure is the law's
/// to mean_tolerance (at most mean_rounds contours in all), each kept only when it comes nearer
/// the measure with the same components and holes.
/// measures(shape) gives (enclosed, boundary): area and length, or volume and area.
template <class Result, class Shape, class Law, class Region, class ContourOptions, class Level,
          class MakeLevel, class Measures>
Result advance_extended(const Shape& shape, double t, double k, const Law& law,
                        const Region& domain, ContourOptions contour_options, Level& now,
                        MakeLevel make_level, Measures measures, bool restored) {
    using Point = typename std::remove_cvref_t<decltype(vertices_of(shape))>::value_type;
    Result result;
    const auto finite = [&law](Point w, double time, Point x) {
        return checked_velocity(w, law.name(), time, x);
    };
    const double predictor_reach = k * now.max_speed() + now.max_bulge();
    contour_options.distance_slack = 2.0 * predictor_reach;
    const auto predictor_bounds = pointwise<Point>(
        [&](Point x) {
            const auto [p, w] = now.closest_point_and_velocity(x);
            const double d = k * norm(w) + now.max_bulge();
            const double reach = distance(x - k * w, p.point) + now.max_bulge();
            return Interval{std::max(p.distance - d, -reach), std::min(p.distance + d, reach)};
        },
        expensive_grain);
    const auto predictor = pointwise<Point>(
        [&](Point x) { return now.distance(x - k * finite(now.velocity(x), t, x)); },
        expensive_grain);
    auto predicted = contour_of(predictor, domain, contour_options, predictor_bounds);
    result.stats.predictor = predicted.stats;
    if (vanished(shape_of(predicted))) return result;  // everything vanished within the step

    auto next = make_level(shape_of(predicted), t + k);
    const auto corrector = pointwise<Point>(
        [&](Point x) {
            const Point foot = x - k * finite(now.velocity(x), t, x);
            const Point w_foot = finite(now.velocity(foot), t, foot);
            const Point w_next = finite(next.velocity(x, w_foot), t + k, x);
            return now.distance(x - (0.5 * k) * (w_foot + w_next));
        },
        expensive_grain);
    const auto contour_corrector = [&] {
        const double reach = 0.5 * k * (now.max_speed() + next.max_speed()) + now.max_bulge();
        contour_options.distance_slack = 2.0 * reach;
        const auto chords = [&now](Point x) { return now.chord_distance(x); };
        return contour_of(corrector, domain, contour_options,
                          distance_bounds<Point>(chords, reach));
    };
    auto corrected = contour_corrector();
    if (law.preserves_area() && !vanished(shape_of(corrected))) {
        const auto [first, boundary] = measures(shape_of(corrected));
        // The law's exact measure: kept, or changing at its rate (a source's injection).
        const double target = measures(shape).first + k * law.invariants().area_rate.value_or(0.0);
        const auto miss = [&](double measure) { return std::abs(target - measure); };
        double slope = k * boundary;  // of the measure against the shift s of the mean
        double s = (target - first) / slope;
        now.add_normal_speed(s);
        next.add_normal_speed(s);
        std::size_t evals = corrected.stats.g_evals;
        corrected = contour_corrector();
        evals += corrected.stats.g_evals;
        // Secant steps while they keep the contour's topology and bring its measure nearer the
        // law's (where the step merges or tears a part the measure may jump with s).
        if (!restored && !vanished(shape_of(corrected))) {
            const ShapeTopology topology = shape_topology(shape_of(corrected));
            double s_before = 0.0, before = first, produced = measures(shape_of(corrected)).first;
            for (int round = 1; round < mean_rounds; ++round) {
                if (miss(produced) <= mean_tolerance * std::abs(target)) break;
                slope = (produced - before) / (s - s_before);
                if (!(slope > 0.25 * k * boundary && slope < 4.0 * k * boundary)) break;
                const double ds = (target - produced) / slope;
                now.add_normal_speed(ds);
                next.add_normal_speed(ds);
                auto other = contour_corrector();
                evals += other.stats.g_evals;
                if (vanished(shape_of(other)) || shape_topology(shape_of(other)) != topology) break;
                const double measure = measures(shape_of(other)).first;
                if (miss(measure) >= miss(produced)) break;
                s_before = std::exchange(s, s + ds);
                before = std::exchange(produced, measure);
                corrected = std::move(other);
            }
        }
        corrected.stats.g_evals = evals;  // all the contours' cost
    }
    result.stats.corrector = corrected.stats;
    shape_of(result) = std::move(shape_of(corrected));
    return result;
}

/// The enclosed measure of an interface (area of curves, volume of a surface) brought back to
/// target by moving its vertices along their normals: shifts of δ = (target − M)/B (B its
/// boundary measure, length or area), each vertex by at most a quarter of its shortest edge,
/// each shift leaving O(δ²) of the difference, and more where vertices were held back: eight
/// shifts at most leave rounding. The measure may have parts, each with its own target (the
/// regions of curves that each keep their area). A vertex stays where it is once a shift makes
/// the interface meet itself at one of its elements (segments or triangles), as a fold of edges
/// far shorter than the shift would. Returns the interface and the measure added in all (0, the
/// interface as given, when no vertex can move). The dimension gives:
///   measure(shape)                  the enclosed measure M of each part
///   shifts(shape, δ)                each vertex's shift: its part's δ along its normal, clamped
///   moved(shape, shifts, held)      the interface with the vertices not held shifted
///   contact(shape)                  two elements that meet, if any (optional pair)
///   corners(shape, element)         the vertices of an element
template <class Shape, class Measure, class Shifts, class Moved, class Contact, class Corners>
std::pair<Shape, double> restored_measure(const Shape& shape, const std::vector<double>& target,
                                          Measure measure, Shifts shifts, Moved moved,
                                          Contact contact, Corners corners) {
    const auto sum = [](const std::vector<double>& m) {
        double total = 0.0;
        for (const double x : m) total += x;
        return total;
    };
    std::pair<Shape, double> out{shape, 0.0};
    std::vector<bool> held(vertices_of(shape).size(), false);
    // One shift from s: the moved interface and the measure it added, or none.
    const auto shift_once = [&](const Shape& s) -> std::optional<std::pair<Shape, double>> {
        const std::vector<double> m = measure(s);
        std::vector<double> missing(m.size());
        for (std::size_t p = 0; p < m.size(); ++p) missing[p] = target[p] - m[p];
        const auto shift = shifts(s, missing);
        for (int attempt = 0; attempt < 16; ++attempt) {
            Shape candidate = moved(s, shift, held);
            const auto met = contact(candidate);
            if (!met) {
                const double added = sum(measure(candidate)) - sum(m);
                return std::pair(std::move(candidate), added);
            }
            bool newly_held = false;
            for (const auto element : {met->first, met->second}) {
                for (const auto i : corners(s, element)) {
                    newly_held = newly_held || !held[i];
                    held[i] = true;
                }
            }
            if (!newly_held) break;
        }
        return std::nullopt;
    };
    for (int shift = 0; shift < 8 && !vanished(out.first); ++shift) {
        auto next = shift_once(out.first);
        if (!next || next->second == 0.0) break;
        out.first = std::move(next->first);
        out.second += next->second;
    }
    return out;
}

}  // namespace slc::detail
