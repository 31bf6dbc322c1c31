// The predictor–corrector step (paper §1.2 Eqs. 4, 5; §4.3 "Semi-Lagrangian evaluation").
#include "slc/evolve/step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "predictor_corrector.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/extension.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/geometry_modules/arclength.hpp"
#include "step_common.hpp"

namespace slc {

int StepOptions::resolved_tree_depth() const {
    if (tree_depth > 0) return tree_depth;
    const int passes = contour.refine_passes < 0 ? 4 : contour.refine_passes;
    // The Whitney extension interpolates on the tree's own triangulation, so there L sets its
    // accuracy: the paper's K + P. Elsewhere the distances are exact at any depth and L only sets
    // the cost; a refinement pass splits about half the segments, so the mean segment shrinks
    // about √2-fold per pass and one level per two passes keeps a few segments in each leaf;
    // beyond four passes only the segments that still miss ε are split, and the rest keep it.
    const int extra = extension == Extension::whitney ? passes : std::min(passes, 4) / 2;
    return std::min(contour.depth + extra, Quadtree::max_supported_depth);
}

Extension StepOptions::resolved_extension(const VelocityLaw& law) const {
    if (extension) return *extension;
    return law.is_field() || law.is_normal_law() ? Extension::direct : Extension::nearest_point;
}

bool StepOptions::resolved_arcs(const VelocityLaw& law) const {
    if (arcs) return *arcs;
    if (resolved_extension(law) == Extension::direct && (law.is_normal_law() || law.is_field()))
        return true;
    const GeometryNeeds needs = law.needs();
    return needs.smooth ||
           (needs.curvature && needs.resolved_module() == GeometryModule::arclength);
}

namespace {

/// The longest segment a step of law reads as part of a smooth curve: under a rigid motion,
/// StepOptions::arc_longest finest cells (the contours' own segments; a user's coarser polygon
/// is moved as the polygon it is), under every other law any.
double longest_smooth_segment(const VelocityLaw& law, const Box& domain, const StepOptions& o) {
    if (!law.invariants().rigid) return std::numeric_limits<double>::infinity();
    return StepOptions::arc_longest * finest_cell(domain, o.contour);
}

/// True where the polygon is read as a smooth curve: at a vertex whose segments u, v turn by at
/// most StepOptions::arc_corner and are each at most `longest`.
bool reads_smooth(Vec2 u, Vec2 v, double longest) {
    return std::abs(turn_angle(u, v)) <= StepOptions::arc_corner && norm2(u) <= longest * longest &&
           norm2(v) <= longest * longest;
}

/// The signed curvature of the circle through each vertex and its two neighbours (−1/R on a
/// circle), or 0 where the curve is not read as smooth there (reads_smooth).
std::vector<double> arc_curvatures(const Interface& curves, double longest) {
    std::vector<double> kappa(curves.size());
    parallel_for(curves.size(), [&](std::size_t i) {
        const Vec2 u = curves.point(i) - curves.point(curves.prev(i));
        const Vec2 v = curves.point(curves.next(i)) - curves.point(i);
        if (reads_smooth(u, v, longest)) kappa[i] = circle_curvature(u, v);
    });
    return kappa;
}

}  // namespace

double finest_cell(const Box& domain, const ContourOptions& contour) {
    return std::ldexp(domain.width(), -contour.depth);
}

std::pair<double, double> step_area_and_length(const Interface& curves, const VelocityLaw& law,
                                               const StepOptions& options, const Box& domain) {
    if (curves.empty() || !options.resolved_arcs(law)) return {area(curves), length(curves)};
    // Level::distance's arc lies y(s) = ½ c² s (1 − s) κ(s) beyond the chord, κ(s) = κa (1 − s)
    // + κb s: it takes c³ (κa + κb) / 24 from the area, and its length is ∫ sqrt(c² + y'(s)²) ds,
    // by three-point Gauss–Legendre.
    constexpr double node = 0.3872983346207417;  // sqrt(0.6) / 2
    constexpr std::array<std::pair<double, double>, 3> gauss{
        {{0.5 - node, 5.0 / 18.0}, {0.5, 8.0 / 18.0}, {0.5 + node, 5.0 / 18.0}}};
    const std::vector<double> kappa =
        arc_curvatures(curves, longest_smooth_segment(law, domain, options));
    double a = area(curves), l = 0.0;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const std::size_t b = curves.next(i);
        const double c = norm(curves.point(b) - curves.point(i));
        const double ka = kappa[i], kb = kappa[b];
        a -= c * c * c * (ka + kb) / 24.0;
        for (const auto& [s, w] : gauss) {
            const double slope =
                0.5 * c * c * (ka * (1.0 - 2.0 * s) + (kb - ka) * s * (2.0 - 3.0 * s));
            l += w * std::sqrt(c * c + slope * slope);
        }
    }
    return {a, l};
}

double step_area(const Interface& curves, const VelocityLaw& law, const StepOptions& options,
                 const Box& domain) {
    return step_area_and_length(curves, law, options, domain).first;
}

double step_length(const Interface& curves, const VelocityLaw& law, const StepOptions& options,
                   const Box& domain) {
    return step_area_and_length(curves, law, options, domain).second;
}

namespace {

/// Γ at one time level: its distance tree and, unless the law is evaluated directly, its vertex
/// velocities and their extension W off Γ; for a normal law evaluated directly, the field's
/// normals and a bound on the law's speed.
class Level {
public:
    /// k: the step, which sets the arclength module's default width.
    Level(const Interface& curves, double t, double k, const VelocityLaw& law, const Box& domain,
          const StepOptions& options)
        : law_(law),
          t_(t),
          longest_smooth_(longest_smooth_segment(law, domain, options)),
          extension_(options.resolved_extension(law)),
          tree_(curves, domain,
                {.depth = options.resolved_tree_depth(),
                 .triangulate = extension_ == Extension::whitney}) {
        // Directly: a flow field needs no W here; a normal law, a bound on its speed.
        if (extension_ != Extension::direct) {
            const GeometryContext context{.tree = &tree_,
                                          .embedded = options.embedded,
                                          .arc_width = options.resolved_arc_width(k),
                                          .step = k};
            u_ = vertex_velocities(law, t, curves, context);
            if (extension_ == Extension::whitney) whitney_.emplace(tree_, u_);
            if (extension_ == Extension::nearest_point && law.constant_speed()) set_shocks();
            for (Vec2 u : u_) max_speed_ = std::max(max_speed_, norm(u));
            for (const auto& [before, after] : sides_)
                max_speed_ = std::max({max_speed_, norm(before), norm(after)});
        } else if (law.is_normal_law()) {
            set_vertex_normals();
            max_speed_ = max_normal_speed();
        }
        if (options.resolved_arcs(law)) {
            kappa_ = arc_curvatures(curves, longest_smooth_);
            for (std::size_t i = 0; i < curves.size(); ++i) {
                const double c2 = norm2(curves.point(curves.next(i)) - curves.point(i));
                const double kappa =
                    std::max(std::abs(kappa_[i]), std::abs(kappa_[curves.next(i)]));
                max_bulge_ = std::max(max_bulge_, 0.125 * c2 * kappa);
            }
        }
    }

    /// W(x) at this level's time, extended from the vertex velocities.
    Vec2 velocity(Vec2 x) const {
        if (extension_ == Extension::whitney) return (*whitney_)(x);
        return velocity(x, tree_.nearest_point(x));
    }
    /// W(x) for the corrector's end of the characteristic through x, which brought `arriving`
    /// from the level before: where x is nearest a shock corner or one of its two sides, the
    /// side whose velocity is nearer `arriving`. A point on a shock's bisector (within rounding
    /// of it) is equally near both sides, and each level may name the other one: the mean of
    /// the two sides' velocities would then move the corner by three quarters of a step where
    /// the characteristic keeps to one side, a jump of G along the bisector that refinement
    /// cannot cross to place the corner.
    Vec2 velocity(Vec2 x, Vec2 arriving) const {
        if (extension_ != Extension::nearest_point || sides_.empty()) return velocity(x);
        const ClosestPoint p = tree_.nearest_point(x);
        const Interface& curves = tree_.curves();
        const auto nearer = [arriving](Vec2 a, Vec2 b) {
            return norm2(a - arriving) <= norm2(b - arriving) ? a : b;
        };
        if (p.t == 0.0 || p.t == 1.0) {
            const std::size_t v = p.t == 0.0 ? p.segment : curves.next(p.segment);
            return shock_[v] ? nearer(sides_[v].first, sides_[v].second) : u_[v];
        }
        const std::size_t a = p.segment, b = curves.next(a);
        if (shock_[a] && norm2(sides_[a].first - arriving) < norm2(sides_[a].second - arriving))
            return sides_[a].first;
        if (shock_[b] && norm2(sides_[b].second - arriving) < norm2(sides_[b].first - arriving))
            return sides_[b].second;
        return velocity(x, p);
    }
    /// The signed distance to this level's Γ: exact to its chords, or to its arcs with
    /// StepOptions::arcs.
    double distance(Vec2 x) const { return distance(tree_.closest_point(x)); }

    /// What a normal law's step needs at a batch of points: F there and the normal the law sees
    /// (field_normal), one closest-point query each, on all worker threads.
    void distances_and_normals(std::span<const Vec2> xs, std::span<double> f,
                               std::span<Vec2> n) const {
        detail::distances_and_normals(
            tree_, xs, f, n, [this](const ClosestPoint& p) { return distance(p); },
            [this](Vec2 x, const ClosestPoint& p) { return field_normal(x, p); });
    }
    /// The normal law's speeds V(t, x_i, n_i) at this level's time, one call of the law for the
    /// batch; NumericalFailure naming the point unless all are finite.
    void normal_speeds(std::span<const Vec2> xs, std::span<const Vec2> n,
                       std::span<double> v) const {
        detail::checked_normal_speeds(law_, t_, xs, n, v);
    }
    /// The closest point of this level's polygon (whatever StepOptions::arcs says) and W(x),
    /// from one closest-point query.
    std::pair<ClosestPoint, Vec2> closest_point_and_velocity(Vec2 x) const {
        const ClosestPoint p = tree_.closest_point(x);
        return {p, velocity(x, p)};
    }
    /// The exact signed distance to this level's polygon, whatever StepOptions::arcs says.
    double chord_distance(Vec2 x) const { return tree_.closest_point(x).distance; }
    /// The most distance() differs from chord_distance(): the largest bulge of an arc.
    double max_bulge() const { return max_bulge_; }
    /// max |W|: both extensions interpolate the vertex velocities (the maximum principle); a
    /// normal law's bound is max_normal_speed().
    double max_speed() const { return max_speed_; }
    /// A normal law's max|V| over the distance field's normals (max_normal_speed()).
    std::optional<double> normal_speed_bound() const { return max_speed_; }
    /// A normal law's speed when it is one number everywhere (VelocityLaw::constant_speed).
    std::optional<double> constant_speed() const { return law_.constant_speed(); }

    /// Adds the normal speed s to every vertex velocity, along the bisectors of the segments'
    /// normals: a move of the mean of a nonlocal law, whose speeds are V − mean.
    void add_normal_speed(double s) {
        const Interface& curves = tree_.curves();
        for (std::size_t v = 0; v < curves.size(); ++v) {
            const Vec2 sum = segment_normal(curves.prev(v)) + segment_normal(v);
            const double length = norm(sum);
            if (length > 0.0) u_[v] += (s / length) * sum;
        }
        if (extension_ == Extension::whitney) whitney_.emplace(tree_, u_);
        max_speed_ = 0.0;
        for (Vec2 u : u_) max_speed_ = std::max(max_speed_, norm(u));
    }

private:
    /// W(x), given the closest point p of this level's polygon to x.
    Vec2 velocity(Vec2 x, const ClosestPoint& p) const {
        if (extension_ == Extension::whitney) return (*whitney_)(x);
        if (sides_.empty() || p.t == 0.0 || p.t == 1.0)
            return nearest_point_extension<Vec2>(tree_.curves(), u_, p);
        const std::size_t a = p.segment, b = tree_.curves().next(a);
        const Vec2 ua = shock_[a] ? sides_[a].second : u_[a];
        const Vec2 ub = shock_[b] ? sides_[b].first : u_[b];
        return (1.0 - p.t) * ua + p.t * ub;
    }

    /// Where a normal law of constant speed moves the two sides of a corner towards each other
    /// (a shrinking convex corner, or the cusp where growing curves meet: a shock, where
    /// characteristics end), each side moves with its own normal's velocity all the way to the
    /// corner, as Huygens' principle has it: interpolating towards the corner's averaged normal
    /// would cut the corner, or fill the cusp, by about a segment each step. Points nearest the
    /// corner itself keep its vertex velocity, and corners whose sides part (rounding into a
    /// fan) keep the interpolation, as the paper has it. (A speed that depends on the normal
    /// is left to the paper's interpolation: at the corners of m = 3's non-convex Wulff shape
    /// the sides' velocities made the shape depend on the grid's orientation.) A corner is a vertex
    /// the polygon does not read as smooth (reads_smooth, as field_normal); sides_[v]: the
    /// velocities of the segments before and after v, at v, where shock_[v].
    /// A law of constant speed keeps no area, so add_normal_speed() never meets shocks.
    void set_shocks() {
        set_vertex_normals();
        const Interface& curves = tree_.curves();
        std::vector<Vec2> at, normals;
        std::vector<std::size_t> corners;
        for (std::size_t v = 0; v < curves.size(); ++v) {
            if (smooth_[v]) continue;
            corners.push_back(v);
            for (std::size_t s : {curves.prev(v), v}) {
                at.push_back(curves.point(v));
                normals.push_back(segment_normal(s));
            }
        }
        if (corners.empty()) return;
        std::vector<double> speeds(at.size());
        normal_speeds(at, normals, speeds);
        for (std::size_t i = 0; i < corners.size(); ++i) {
            const Vec2 before = normals[2 * i], after = normals[2 * i + 1];
            const double turn = cross(before, after);  // > 0 at a convex corner
            if (!(speeds[2 * i] * turn < 0.0 && speeds[2 * i + 1] * turn < 0.0)) continue;
            if (sides_.empty()) {
                sides_.assign(curves.size(), {});
                shock_.assign(curves.size(), 0);
            }
            shock_[corners[i]] = 1;
            sides_[corners[i]] = {speeds[2 * i] * before, speeds[2 * i + 1] * after};
        }
    }

    /// distance(x), given the closest point p of this level's polygon to x.
    double distance(const ClosestPoint& p) const {
        if (kappa_.empty() || p.t == 0.0 || p.t == 1.0) return p.distance;
        const Interface& curves = tree_.curves();
        const std::size_t b = curves.next(p.segment);
        const double c2 = norm2(curves.point(b) - curves.point(p.segment));
        const double kappa = (1.0 - p.t) * kappa_[p.segment] + p.t * kappa_[b];
        // The arc through the segment's ends with curvature κ (C = −1/R convention) lies
        // ½ c² t (1 − t) |κ| outside the chord at t where the curve is convex.
        return p.distance + 0.5 * c2 * p.t * (1.0 - p.t) * kappa;
    }

    /// The outward unit normal of segment s.
    Vec2 segment_normal(std::size_t s) const {
        const Interface& curves = tree_.curves();
        const Vec2 e = curves.point(curves.next(s)) - curves.point(s);
        return -perp(e) / norm(e);  // the outside is on the right
    }

    /// The normal a normal law sees at x, given its closest point p: ∇F, except that the
    /// polygon's vertices where it reads as smooth (reads_smooth: turning by at most
    /// StepOptions::arc_corner, and under a rigid motion segments at most
    /// StepOptions::arc_longest cells) are read as points of a smooth curve. Inside a segment, the
    /// normal interpolated linearly between its ends' and normalized, where an end's normal is its
    /// vertex's pseudo-normal (the normalized sum of its two segments' normals) at a smooth vertex
    /// and the segment's own at a corner; nearest a smooth vertex, its pseudo-normal; nearest a
    /// corner, the direction from it, sign F (x − y)/|x − y| (its pseudo-normal within a relative
    /// 1e−9 of it). The field is then continuous across the bisectors inside a smooth curve, where
    /// ∇F jumps by the turning angle at every vertex (a jump a direction-dependent speed would turn
    /// into a jump of G), while corners keep the exact field: the fan of normals in their wedge,
    /// the shock on the bisector.
    Vec2 field_normal(Vec2 x, const ClosestPoint& p) const {
        const Interface& curves = tree_.curves();
        if (p.t > 0.0 && p.t < 1.0) {
            const Vec2 own = segment_normal(p.segment);
            const std::size_t b = curves.next(p.segment);
            const Vec2 sum = (1.0 - p.t) * (smooth_[p.segment] ? vertex_normals_[p.segment] : own) +
                             p.t * (smooth_[b] ? vertex_normals_[b] : own);
            const double s = norm(sum);
            return s > 0.0 ? sum / s : own;
        }
        const std::size_t v = p.t == 0.0 ? p.segment : curves.next(p.segment);
        if (smooth_[v]) return vertex_normals_[v];
        const std::size_t before = curves.prev(v);
        const Vec2 d = x - curves.point(v);
        const double r = norm(d);
        const double shorter = std::min(norm(curves.point(v) - curves.point(before)),
                                        norm(curves.point(curves.next(v)) - curves.point(v)));
        if (r > 1e-9 * shorter) return (p.distance < 0.0 ? -1.0 / r : 1.0 / r) * d;
        return vertex_normals_[v];
    }

    /// Each vertex's pseudo-normal, and whether the polygon reads as smooth there (reads_smooth,
    /// field_normal).
    void set_vertex_normals() {
        const Interface& curves = tree_.curves();
        vertex_normals_.resize(curves.size());
        smooth_.resize(curves.size());
        for (std::size_t v = 0; v < curves.size(); ++v) {
            const Vec2 a = segment_normal(curves.prev(v)), b = segment_normal(v);
            const Vec2 sum = a + b;
            const double s = norm(sum);
            vertex_normals_[v] = s > 0.0 ? sum / s : b;
            smooth_[v] =
                reads_smooth(curves.point(v) - curves.point(curves.prev(v)),
                             curves.point(curves.next(v)) - curves.point(v), longest_smooth_);
        }
    }

    /// A bound on |V| over every normal of the distance field: V at each vertex for the normals
    /// of its two segments and for directions between them at most 0.02 rad apart (the normals
    /// of the points nearest that vertex), raised by a tenth for the directions between the
    /// samples and for V's change over a step's reach.
    double max_normal_speed() const {
        const Interface& curves = tree_.curves();
        std::vector<Vec2> at, normals;
        for (std::size_t v = 0; v < curves.size(); ++v) {
            const Vec2 a = segment_normal(curves.prev(v)), b = segment_normal(v);
            const double turn = turn_angle(a, b);
            const int samples = 1 + static_cast<int>(std::ceil(std::abs(turn) / 0.02));
            for (int j = 0; j <= samples; ++j) {
                const double angle = turn * j / samples;
                const double c = std::cos(angle), s = std::sin(angle);
                at.push_back(curves.point(v));
                normals.push_back({c * a.x - s * a.y, s * a.x + c * a.y});
            }
        }
        std::vector<double> speeds(at.size());
        normal_speeds(at, normals, speeds);
        double most = 0.0;
        for (double v : speeds) most = std::max(most, std::abs(v));
        return 1.1 * most;
    }

    const VelocityLaw& law_;
    double t_;
    double longest_smooth_;  ///< the longest segment read as smooth (longest_smooth_segment)
    Extension extension_;
    DistanceTree tree_;
    std::vector<Vec2> u_;
    double max_speed_ = 0.0;
    std::vector<double> kappa_;         ///< arc curvatures at the vertices, empty without arcs
    std::vector<Vec2> vertex_normals_;  ///< pseudo-normals, for a normal law (field_normal)
    std::vector<char> smooth_;          ///< turning by at most arc_corner, for a normal law
    std::vector<char> shock_;           ///< corners whose sides meet (set_shocks); empty: none
    std::vector<std::pair<Vec2, Vec2>> sides_;  ///< their sides' velocities at them
    double max_bulge_ = 0.0;
    std::optional<WhitneyExtension<Vec2>> whitney_;
};

StepResult advance_contours(const Interface& curves, double t, double k, const VelocityLaw& law,
                            const Box& domain, const StepOptions& options) {
    if (!(k > 0.0) || !std::isfinite(k)) {
        throw InvalidInput(fmt::format("time step must be positive and finite, got {}", k));
    }
    const Extension extension = options.resolved_extension(law);
    if (extension == Extension::direct && !law.is_field() && !law.is_normal_law()) {
        throw InvalidInput(
            fmt::format("velocity '{}' is not defined off the curve: use the nearest-point or "
                        "Whitney extension",
                        law.name()));
    }
    const auto make_level = [&](const Interface& c, double time) {
        return Level(c, time, k, law, domain, options);
    };
    // G is a distance carried by the flow only in a flow field's direct step
    // (bends_through_centres).
    ContourOptions looped = options.contour;
    looped.bends_through_centres = false;
    if (extension == Extension::direct && law.is_normal_law())
        return detail::advance_normal_law<StepResult>(curves, t, k, domain, looped, make_level);
    Level now(curves, t, k, law, domain, options);
    if (extension == Extension::direct)
        return detail::advance_flow<StepResult>(curves, t, k, law, domain, options.contour, now);
    return detail::advance_extended<StepResult>(
        curves, t, k, law, domain, looped, now, make_level,
        [&](const Interface& c) { return step_area_and_length(c, law, options, domain); },
        options.resolved_area_correction(law));
}

}  // namespace

AreaRestored restore_region_areas(const Interface& curves, std::span<const std::size_t> region,
                                  std::span<const double> target) {
    const auto areas = [&](const Interface& c) {
        std::vector<double> a(target.size(), 0.0);
        for (std::size_t j = 0; j < c.curve_count(); ++j) a[region[j]] += signed_area(c.curve(j));
        return a;
    };
    // Each vertex moves along the bisector of its segments' normals, by at most a quarter of the
    // shorter of them: a sharp turn or a short segment would otherwise fold the curve; what it
    // holds back, the next shift gives. A zigzag of segments far shorter than the shift, left
    // where the zero set passes a cell corner, folds under any shift: its vertices are held.
    const auto shifts = [&](const Interface& c, const std::vector<double>& missing) {
        std::vector<double> lengths(target.size(), 0.0);
        for (std::size_t i = 0; i < c.size(); ++i) {
            const Segment s = c.segment(i);
            lengths[region[c.curve_of(i)]] += distance(s.a, s.b);
        }
        std::vector<Vec2> shift(c.size());
        for (std::size_t i = 0; i < c.size(); ++i) {
            const std::size_t p = region[c.curve_of(i)];
            const double delta = missing[p] / lengths[p];
            const Vec2 u = c.point(i) - c.point(c.prev(i));
            const Vec2 v = c.point(c.next(i)) - c.point(i);
            const Vec2 n = -perp(u / norm(u) + v / norm(v));  // the outside is on the right
            const double len = norm(n);
            const double reach = 0.25 * std::min(norm(u), norm(v));
            if (len > 0.0 && std::isfinite(len))
                shift[i] = std::clamp(delta / len, -reach, reach) * n;
        }
        return shift;
    };
    const auto moved = [](const Interface& c, const std::vector<Vec2>& shift,
                          const std::vector<bool>& held) {
        std::vector<std::vector<Vec2>> points = c.curves();
        for (std::size_t k = 0, first = 0; k < points.size(); first += points[k].size(), ++k) {
            for (std::size_t j = 0; j < points[k].size(); ++j)
                if (!held[first + j]) points[k][j] += shift[first + j];
        }
        return Interface(points);
    };
    const auto ends = [](const Interface& c, std::size_t s) {
        return std::array<std::size_t, 2>{s, c.next(s)};
    };
    auto [out, added] = detail::restored_measure(
        curves, std::vector<double>(target.begin(), target.end()), areas, shifts, moved,
        [](const Interface& c) { return find_crossing(c); }, ends);
    return {std::move(out), added};
}

AreaRestored restore_area(const Interface& curves, double target) {
    const std::vector<std::size_t> one(curves.curve_count(), 0);
    return restore_region_areas(curves, one, std::span(&target, 1));
}

namespace {

/// The regions of `after` matched to those of `before` (region r of after is match[r] of
/// before): each to the one whose outer curve's mean vertex is nearest its own, when that pairs
/// them one to one; nothing when the regions merged, split or vanished.
std::optional<std::vector<std::size_t>> matched_regions(const Interface& before,
                                                        const Interface& after) {
    const auto outer_means = [](const Interface& c) {
        std::vector<Vec2> p;
        for (std::size_t j = 0; j < c.curve_count(); ++j) {
            if (!(signed_area(c.curve(j)) > 0)) continue;
            Vec2 sum{};
            for (const Vec2 x : c.curve(j)) sum += x;
            p.push_back(sum / static_cast<double>(c.curve(j).size()));
        }
        return p;
    };
    const std::vector<Vec2> from = outer_means(before), to = outer_means(after);
    if (from.size() != to.size()) return std::nullopt;
    std::vector<std::size_t> match(to.size());
    std::vector<bool> taken(from.size(), false);
    for (std::size_t r = 0; r < to.size(); ++r) {
        std::size_t best = 0;
        for (std::size_t q = 1; q < from.size(); ++q)
            if (distance(to[r], from[q]) < distance(to[r], from[best])) best = q;
        if (taken[best]) return std::nullopt;
        taken[best] = true;
        match[r] = best;
    }
    return match;
}

/// The regions of the curves after a step brought back to their areas before it (the one
/// holding the law's source grown by k × its rate), or nothing when the regions changed.
std::optional<AreaRestored> restored_regions(const Interface& before, const Interface& after,
                                             double k, const Invariants& kept) {
    const std::optional<std::vector<std::size_t>> match = matched_regions(before, after);
    if (!match) return std::nullopt;
    const std::vector<std::size_t> was = curve_regions(before);
    std::vector<double> had(match->size(), 0.0);
    for (std::size_t c = 0; c < before.curve_count(); ++c)
        had[was[c]] += signed_area(before.curve(c));
    std::optional<std::size_t> fed;
    if (kept.area_rate && kept.area_source) fed = region_containing(before, was, *kept.area_source);
    std::vector<double> target(match->size());
    for (std::size_t r = 0; r < target.size(); ++r) {
        const std::size_t q = (*match)[r];
        target[r] = had[q] + (fed == q ? k * *kept.area_rate : 0.0);
    }
    return restore_region_areas(after, curve_regions(after), target);
}

}  // namespace

StepResult advance(const Interface& curves, double t, double k, const VelocityLaw& law,
                   const Box& domain, const StepOptions& options) {
    StepResult result = advance_contours(curves, t, k, law, domain, options);
    if (options.resolved_area_correction(law) && !result.curves.empty()) {
        // The law's exact area: kept, or growing at its rate (a source's injection); each
        // region's own while they neither merge nor vanish, if the law keeps them.
        const Invariants kept = law.invariants();
        const double rate = kept.area_rate.value_or(0.0);
        std::optional<AreaRestored> restored;
        if (kept.keeps_region_areas) restored = restored_regions(curves, result.curves, k, kept);
        if (!restored) restored = restore_area(result.curves, area(curves) + k * rate);
        result.curves = std::move(restored->curves);
        result.stats.area_correction = restored->added;
    }
    return result;
}

}  // namespace slc
