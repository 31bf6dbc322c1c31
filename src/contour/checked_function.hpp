// G as the contouring stages call it, written once for the plane and space (internal to the
// contour module): evaluated in batches, counted, and checked finite, so that no NaN reaches a
// sign test.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include "slc/contour/implicit_function.hpp"
#include "slc/core/error.hpp"
#include "slc/core/point_text.hpp"
#include "slc/core/space.hpp"

namespace slc::contouring {

/// G in batches, counted into `count`; a value that is not finite is NumericalFailure naming the
/// point.
template <int dim>
class CheckedFunction {
public:
    using Point = PointOf<dim>;  ///< Vec2 or Vec3
    CheckedFunction(BatchRef<double, Point> g, std::size_t& count) : g_(g), count_(&count) {}

    void operator()(std::span<const Point> points, std::span<double> values) const {
        SLC_ASSERT(points.size() == values.size(), "one value per point");
        if (points.empty()) return;
        g_(points, values);
        *count_ += points.size();
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (!std::isfinite(values[i])) {
                throw NumericalFailure(fmt::format("G is not finite at {}: got {}",
                                                   point_text(points[i], 6), values[i]));
            }
        }
    }

private:
    BatchRef<double, Point> g_;
    std::size_t* count_;
};

/// G in the plane (contour()).
using CountingFunction = CheckedFunction<2>;
/// G in space (contour_surface()).
using SpaceEvaluator = CheckedFunction<3>;

}  // namespace slc::contouring
