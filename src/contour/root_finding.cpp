// Batched bracketed root finding (paper §2.1 "Bisection", §2.2 "Bisect"): Brent's method, the
// Illinois variant of regula falsi, or plain bisection, on many brackets in lockstep rounds.
// Every method works in the parameter t of the bracket [a, b] and keeps a sign change inside.
#include "slc/contour/root_finding.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// A bracket counts as shrunk to rounding size when its length is below this many units of
/// rounding of its coordinates: then no point strictly inside is left to try.
constexpr double stall_ulps = 4.0;

/// Illinois safeguard: after n steps the bracket must be shorter than 2^(−n/3) of its start, a
/// third of bisection's rate, or the next step bisects. Illinois is far faster on smooth G, so this
/// only fires on bad G and caps the cost at about three times that of bisection.
constexpr double illinois_halvings_per_step = 1.0 / 3.0;

/// One bracket, in the parameter t of [a, b]. For bisection and Illinois the sign change lies in
/// [lo, hi]; for Brent, between b (the best point so far) and c (the contrapoint), with a the
/// previous b, d the last step and e the one before (Brent 1973, ch. 4).
struct State {
    double lo = 0.0, hi = 1.0;
    double g_lo = 0.0, g_hi = 0.0;  ///< true values at lo and hi
    double f_lo = 0.0, f_hi = 0.0;  ///< the values regula falsi uses (Illinois halves them)
    int last_replaced = 0;          ///< Illinois: −1 lo was replaced last step, +1 hi, 0 none
    double a = 0.0, b = 1.0, c = 1.0, fa = 0.0, fb = 0.0, fc = 0.0, d = 1.0, e = 1.0;
    double tol = 0.0;   ///< stall length in t
    double jump = 0.0;  ///< jump_slope times the bracket's length: the secant bound in t
    int steps = 0;
    double t = 0.0;  ///< the iterate being evaluated
};

/// The largest magnitude of a coordinate of p.
double largest_magnitude(Vec2 p) { return std::max(std::abs(p.x), std::abs(p.y)); }
double largest_magnitude(Vec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); }

template <class Point>
void check_bracket(const BasicBracket<Point>& b, std::size_t i) {
    const bool finite =
        is_finite(b.a) && is_finite(b.b) && std::isfinite(b.ga) && std::isfinite(b.gb);
    if (!finite || !((b.ga <= 0.0 && b.gb >= 0.0) || (b.ga >= 0.0 && b.gb <= 0.0))) {
        throw InvalidInput(
            fmt::format("find_roots: bracket {} must have finite ends with G of opposite signs, "
                        "got G = {} and {}",
                        i, b.ga, b.gb));
    }
}

template <class Point>
State initial_state(const BasicBracket<Point>& br, double jump_slope) {
    State s;
    s.g_lo = s.f_lo = s.fa = br.ga;
    s.g_hi = s.f_hi = s.fb = s.fc = br.gb;
    const double length = distance(br.a, br.b);
    const double scale = std::max({largest_magnitude(br.a), largest_magnitude(br.b), length});
    s.tol =
        length > 0.0 ? stall_ulps * std::numeric_limits<double>::epsilon() * scale / length : 1.0;
    s.jump = jump_slope * length;
    return s;
}

/// Illinois: regula falsi on the (modified) end values, or the midpoint when regula falsi leaves
/// the open bracket or the safeguard demands it. nullopt when the bracket has stalled.
std::optional<double> illinois_next(const State& s, RootMethod method) {
    if (s.hi - s.lo <= s.tol) return std::nullopt;
    if (std::abs(s.g_lo) + std::abs(s.g_hi) > s.jump * (s.hi - s.lo)) return std::nullopt;
    const double mid = 0.5 * (s.lo + s.hi);
    if (method == RootMethod::bisection) return mid;
    if (s.hi - s.lo > std::exp2(-illinois_halvings_per_step * s.steps)) return mid;
    const double t = (s.lo * s.f_hi - s.hi * s.f_lo) / (s.f_hi - s.f_lo);
    return t > s.lo && t < s.hi ? t : mid;
}

/// Replaces the end whose sign g shares. Illinois rule: when the same end is replaced twice
/// running, the value kept at the other end is halved, which pulls the next regula falsi step
/// across the root and restores superlinear convergence.
void illinois_update(State& s, double g) {
    if ((g < 0.0) == (s.g_lo < 0.0)) {
        s.lo = s.t;
        s.g_lo = s.f_lo = g;
        if (s.last_replaced == -1) s.f_hi *= 0.5;
        s.last_replaced = -1;
    } else {
        s.hi = s.t;
        s.g_hi = s.f_hi = g;
        if (s.last_replaced == +1) s.f_lo *= 0.5;
        s.last_replaced = +1;
    }
}

/// Brent: the next iterate by inverse quadratic interpolation or the secant through the last two
/// iterates, accepted only if it falls well inside the bracket and shrinks faster than bisection
/// would; else the midpoint. nullopt when the bracket has stalled.
std::optional<double> brent_next(State& s) {
    if ((s.fb > 0.0) == (s.fc > 0.0)) {
        s.c = s.a;
        s.fc = s.fa;
        s.e = s.d = s.b - s.a;
    }
    if (std::abs(s.fc) < std::abs(s.fb)) {
        s.a = s.b, s.b = s.c, s.c = s.a;
        s.fa = s.fb, s.fb = s.fc, s.fc = s.fa;
    }
    const double xm = 0.5 * (s.c - s.b);
    if (std::abs(xm) <= s.tol) return std::nullopt;
    if (std::abs(s.fb) + std::abs(s.fc) > s.jump * std::abs(s.c - s.b)) return std::nullopt;
    if (std::abs(s.e) >= s.tol && std::abs(s.fa) > std::abs(s.fb)) {
        const double ratio = s.fb / s.fa;
        double p, q;
        if (s.a == s.c) {  // secant
            p = 2.0 * xm * ratio;
            q = 1.0 - ratio;
        } else {  // inverse quadratic interpolation
            const double qa = s.fa / s.fc, r = s.fb / s.fc;
            p = ratio * (2.0 * xm * qa * (qa - r) - (s.b - s.a) * (r - 1.0));
            q = (qa - 1.0) * (r - 1.0) * (ratio - 1.0);
        }
        if (p > 0.0) q = -q;
        p = std::abs(p);
        if (2.0 * p < std::min(3.0 * xm * q - std::abs(s.tol * q), std::abs(s.e * q))) {
            s.e = s.d;
            s.d = p / q;
        } else {
            s.d = s.e = xm;
        }
    } else {
        s.d = s.e = xm;
    }
    s.a = s.b;
    s.fa = s.fb;
    s.b += std::abs(s.d) > s.tol ? s.d : std::copysign(s.tol, xm);
    return s.b;
}

/// The point reported when a bracket stalls (G jumps across zero): the better end of the tiny
/// bracket that was evaluated (never a given end, so the root stays strictly inside).
template <class Point>
BasicRoot<Point> stalled_root(const State& s, const BasicBracket<Point>& br, RootMethod method) {
    double t, g;
    if (method == RootMethod::brent) {
        const bool b_given = s.b == 0.0 || s.b == 1.0;
        t = b_given ? s.c : s.b;
        g = b_given ? s.fc : s.fb;
    } else {
        const bool take_lo = s.lo > 0.0 && (s.hi == 1.0 || std::abs(s.g_lo) <= std::abs(s.g_hi));
        t = take_lo ? s.lo : s.hi;
        g = take_lo ? s.g_lo : s.g_hi;
    }
    return {br.a + t * (br.b - br.a), t, g, s.steps, false};
}

/// find_roots for points of either dimension.
template <class Point, class G>
std::vector<BasicRoot<Point>> find_roots_in(G g, std::span<const BasicBracket<Point>> brackets,
                                            const RootOptions& options) {
    if (!(options.eta > 0.0) || !std::isfinite(options.eta)) {
        throw InvalidInput(fmt::format("find_roots: eta must be positive, got {}", options.eta));
    }
    if (!(options.jump_slope > 0.0)) {
        throw InvalidInput(
            fmt::format("find_roots: jump_slope must be positive, got {}", options.jump_slope));
    }
    std::vector<State> states(brackets.size());
    std::vector<BasicRoot<Point>> roots(brackets.size());
    std::vector<std::size_t> active;
    for (std::size_t i = 0; i < brackets.size(); ++i) {
        const auto& br = brackets[i];
        check_bracket(br, i);
        states[i] = initial_state(br, options.jump_slope);
        if (std::abs(br.ga) <= options.eta || std::abs(br.gb) <= options.eta) {
            const bool at_a = std::abs(br.ga) <= std::abs(br.gb);
            roots[i] = {at_a ? br.a : br.b, at_a ? 0.0 : 1.0, at_a ? br.ga : br.gb, 0, true};
        } else {
            active.push_back(i);
        }
    }
    const bool brent = options.method == RootMethod::brent;
    std::vector<Point> points;
    std::vector<double> values;
    while (!active.empty()) {
        // Next iterates; stalled brackets leave the round.
        std::size_t kept = 0;
        points.clear();
        for (std::size_t i : active) {
            State& s = states[i];
            const std::optional<double> t =
                brent ? brent_next(s) : illinois_next(s, options.method);
            if (!t) {
                roots[i] = stalled_root(s, brackets[i], options.method);
                continue;
            }
            s.t = *t;
            points.push_back(brackets[i].a + s.t * (brackets[i].b - brackets[i].a));
            active[kept++] = i;
        }
        active.resize(kept);
        values.assign(points.size(), 0.0);
        if (!points.empty()) g(points, values);
        kept = 0;
        for (std::size_t k = 0; k < active.size(); ++k) {
            const std::size_t i = active[k];
            State& s = states[i];
            ++s.steps;
            if (std::abs(values[k]) <= options.eta) {
                roots[i] = {points[k], s.t, values[k], s.steps, true};
                continue;
            }
            if (brent) {
                s.fb = values[k];
            } else {
                illinois_update(s, values[k]);
            }
            active[kept++] = i;
        }
        active.resize(kept);
    }
    return roots;
}

}  // namespace

std::vector<Root> find_roots(BatchFunctionRef g, std::span<const Bracket> brackets,
                             const RootOptions& options) {
    return find_roots_in<Vec2>(g, brackets, options);
}

std::vector<Root3> find_roots(SpaceFunctionRef g, std::span<const Bracket3> brackets,
                              const RootOptions& options) {
    return find_roots_in<Vec3>(g, brackets, options);
}

}  // namespace slc
