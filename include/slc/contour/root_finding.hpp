/// @file
/// Bracketed root finding along segments of the plane or of space, many brackets at once (paper
/// §2.1 "Bisection" and §2.2 "Bisect"). The paper bisects; by default we use Brent's method, which
/// keeps the bracket like bisection but converges superlinearly on smooth G (secant and inverse
/// quadratic steps), and falls back to bisection steps whenever interpolation does not shrink the
/// bracket fast enough, so that it is never much slower than bisection on a bad G.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "slc/contour/implicit_function.hpp"
#include "slc/core/vec2.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

/// How a bracket is shrunk.
enum class RootMethod {
    brent,      ///< Brent's method (default): inverse quadratic / secant, bisection safeguard
    illinois,   ///< regula falsi with the Illinois halving, safeguarded by bisection
    bisection,  ///< plain bisection, the paper's method: one bit per evaluation
};

/// A segment [a, b] on whose ends G has opposite signs: ga = G(a), gb = G(b), ga·gb ≤ 0.
template <class Point>
struct BasicBracket {
    Point a;          ///< one end
    Point b;          ///< the other end
    double ga = 0.0;  ///< G(a)
    double gb = 0.0;  ///< G(b), of the opposite sign (or zero)
};
/// A bracket in the plane.
using Bracket = BasicBracket<Vec2>;
/// A bracket in space.
using Bracket3 = BasicBracket<Vec3>;

/// Tolerances of find_roots.
struct RootOptions {
    double eta = 1e-10;                     ///< η: a point with |G| ≤ η is a root
    RootMethod method = RootMethod::brent;  ///< how brackets are shrunk
    /// Λ_jump > 0: a bracket whose end values satisfy |G(lo)| + |G(hi)| > Λ_jump·|hi − lo| is
    /// given up as a jump of G across zero (a G with |∇G| ≤ Λ_jump has no such bracket), instead
    /// of being bisected to rounding size. Infinite (the default): only rounding stops a bracket.
    double jump_slope = std::numeric_limits<double>::infinity();
};

/// The result for one bracket.
template <class Point>
struct BasicRoot {
    Point point;          ///< a + t (b − a)
    double t = 0.0;       ///< in (0, 1); 0 or 1 only when |G| ≤ η at that given end
    double value = 0.0;   ///< G(point)
    int evaluations = 0;  ///< G evaluations spent on this bracket
    /// |value| ≤ η. False only when the bracket shrank to rounding size first, or G's secant
    /// across it exceeded jump_slope, which happens only where G jumps across zero; point is then
    /// the better end of that bracket.
    bool converged = false;
};
/// A root in the plane.
using Root = BasicRoot<Vec2>;
/// A root in space.
using Root3 = BasicRoot<Vec3>;

/// Shrinks every bracket until G at its current iterate satisfies |G| ≤ η, keeping a sign change
/// inside at every step. Each round evaluates the iterates of all unfinished brackets in one batch
/// of g, so the rounds, not the brackets, are sequential. Never evaluates G at a bracket's ends
/// (their values are given; an end with |G| ≤ η is returned at once) nor twice at one point.
///
/// Cost per bracket, for G with a Lipschitz constant Λ and bracket length ℓ: bisection needs
/// log2(Λ ℓ / η) evaluations (about 30 on a tree edge); Brent and Illinois need 2–4 when G is
/// smooth along the bracket, and never many more than bisection otherwise. Results do not depend on
/// the thread count. Throws InvalidInput if a bracket has no sign change or a non-finite end, or
/// eta is not positive.
std::vector<Root> find_roots(BatchFunctionRef g, std::span<const Bracket> brackets,
                             const RootOptions& options);
/// The same in space.
std::vector<Root3> find_roots(SpaceFunctionRef g, std::span<const Bracket3> brackets,
                              const RootOptions& options);

}  // namespace slc
