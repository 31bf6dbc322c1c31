// libFuzzer target: the whole pipeline on a small fuzzed interface — validation, the distance tree
// (checked against brute force at every vertex of the contour), and one adaptive contour of the
// exact signed distance. Coordinates are 16-bit integers on a 1/1024 lattice in [-32, 32]², so
// that the fuzzer easily makes collinear, touching and nearly coincident points; a few bytes
// choose the domain, the depths and the tolerances.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "slc/contour/contour.hpp"
#include "slc/core/error.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/geometry/segment.hpp"
#include "slc/geometry/validate.hpp"

namespace {

double lattice(FuzzedDataProvider& in) { return in.ConsumeIntegral<std::int16_t>() / 1024.0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    const double half_width = std::ldexp(1.0, in.ConsumeIntegralInRange(-2, 6));
    const int tree_depth = in.ConsumeIntegralInRange(0, 10);
    slc::ContourOptions options;
    options.depth = in.ConsumeIntegralInRange(0, 6);
    options.refine_passes = in.ConsumeIntegralInRange(0, 3);
    options.eps = std::ldexp(1.0, -in.ConsumeIntegralInRange(4, 20));
    std::vector<std::vector<slc::Vec2>> raw(in.ConsumeIntegralInRange(1, 4));
    for (auto& curve : raw) {
        curve.resize(in.ConsumeIntegralInRange(0, 24));
        for (slc::Vec2& p : curve) p = {lattice(in), lattice(in)};
    }
    const slc::Box domain = slc::Box::centered_square(half_width);
    try {
        const slc::Interface curves = slc::prepare_interface(raw, domain).curves;
        const slc::DistanceTree tree(curves, domain, {.depth = tree_depth, .triangulate = false});
        const auto exact = [&tree](std::span<const slc::Vec2> x, std::span<double> v) {
            const std::vector<double> f = tree.signed_distances(x);
            std::copy(f.begin(), f.end(), v.begin());
        };
        const slc::ContourResult r = slc::contour(exact, domain, options);
        // The tree agrees with brute force at the contour's vertices: the exactness of §1.3.
        for (const slc::Vec2 x : r.curves.points()) {
            const double fast = std::abs(tree.closest_point(x).distance);
            const double slow = std::abs(slc::closest_point_brute_force(curves, x).distance);
            if (std::abs(fast - slow) > 1e-12 * (1.0 + slow)) __builtin_trap();
        }
    } catch (const slc::InvalidInput&) {
    } catch (const slc::NumericalFailure&) {
    }
    return 0;
}
