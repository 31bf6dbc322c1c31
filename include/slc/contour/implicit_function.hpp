/// @file
/// Implicit functions for contouring (paper §2): a function G of the plane or of space that can be
/// evaluated at any point and nothing more (no derivatives, no grid). The contouring module hands G
/// whole batches of points (one per tree level, per root-finding round, per refinement pass) so
/// that G can evaluate them on all cores (DESIGN §5).
#pragma once

#include <concepts>
#include <cstddef>
#include <limits>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>

#include "slc/core/parallel.hpp"
#include "slc/core/vec2.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

/// Bounds on a value: lo ≤ G ≤ hi. {−∞, ∞} says nothing.
struct Interval {
    double lo = -std::numeric_limits<double>::infinity();  ///< lower bound
    double hi = std::numeric_limits<double>::infinity();   ///< upper bound
};

/// A function G of the plane (Point Vec2) or of space (Vec3) evaluated on batches: g(points,
/// values) sets values[i] = G(points[i]) for every i, with values.size() == points.size(). It may
/// use all worker threads, but each value must depend only on its point: not on the thread count,
/// nor on the rest of the batch. Value is double for G itself, Interval for bounds on G.
template <class G, class Value = double, class Point = Vec2>
concept BatchFunction = std::invocable<const G&, std::span<const Point>, std::span<Value>>;

/// A non-owning reference to any BatchFunction with values of type Value (a function, a lambda,
/// any callable object), like std::function_ref: the referenced callable must outlive the
/// reference. Type erasure costs one indirect call per batch, which is nothing beside the batch
/// itself, and lets the contouring algorithm live in compiled sources.
template <class Value, class Point = Vec2>
class BatchRef {
public:
    /// Refers to g, which must outlive the reference (a temporary does not).
    template <class G>
    requires(BatchFunction<G, Value, Point> && !std::same_as<std::remove_cvref_t<G>, BatchRef>)
        BatchRef(const G& g)
    noexcept  // implicit, as std::function_ref
        : call_(&call<G>) {
        if constexpr (std::is_function_v<G>) {
            target_.function = reinterpret_cast<void (*)()>(&g);
        } else {
            target_.object = static_cast<const void*>(std::addressof(g));
        }
    }

    /// Calls the referenced function: values[i] = G(points[i]), values.size() == points.size().
    void operator()(std::span<const Point> points, std::span<Value> values) const {
        call_(target_, points, values);
    }

private:
    /// The referenced callable: an object, or a function (whose pointer may not become void*).
    union Target {
        const void* object;
        void (*function)();
    };

    template <class G>
    static void call(Target g, std::span<const Point> points, std::span<Value> values) {
        if constexpr (std::is_function_v<G>) {
            reinterpret_cast<G*>(g.function)(points, values);
        } else {
            (*static_cast<const G*>(g.object))(points, values);
        }
    }

    Target target_{};
    void (*call_)(Target, std::span<const Point>, std::span<Value>);
};

/// A reference to a BatchFunction that evaluates G.
using BatchFunctionRef = BatchRef<double>;
/// A reference to a BatchFunction that bounds G: an Interval holding G at each point.
using BatchBoundsRef = BatchRef<Interval>;
/// A reference to a BatchFunction that evaluates G in space.
using SpaceFunctionRef = BatchRef<double, Vec3>;
/// A reference to a BatchFunction that bounds G in space.
using SpaceBoundsRef = BatchRef<Interval, Vec3>;

/// The BatchFunction that evaluates a pointwise function f(Point) (Vec2 by default; Vec3 for
/// space) at every point of a batch on all worker threads, for batches of at least min_iterations
/// points (pass expensive_grain for an f that costs a microsecond or more). f returns a double
/// (G), or an Interval (bounds on G). f must be safe to call concurrently.
template <class Point = Vec2, class F>
requires std::is_invocable_r_v<double, const F&, Point> ||
    std::is_invocable_r_v<Interval, const F&, Point>
auto pointwise(F f, std::size_t min_iterations = parallel_grain) {
    using Value =
        std::conditional_t<std::is_invocable_r_v<double, const F&, Point>, double, Interval>;
    return
        [f = std::move(f), min_iterations](std::span<const Point> points, std::span<Value> values) {
            parallel_for(
                points.size(), [&](std::size_t i) { values[i] = f(points[i]); }, min_iterations);
        };
}

}  // namespace slc
