// Built-in shapes sampled as counterclockwise polygons.
#include "slc/geometry/shapes.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"

namespace slc::shapes {
namespace {

void require_count(int n, int least, const char* what) {
    if (n < least)
        throw InvalidInput(fmt::format("{} needs at least {} vertices, got {}", what, least, n));
}

}  // namespace

std::vector<Vec2> polar(Vec2 centre, const std::function<double(double)>& r, int n, double phase) {
    require_count(n, 3, "a polar curve");
    std::vector<Vec2> pts;
    pts.reserve(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
        const double theta = phase + 2.0 * std::numbers::pi * k / n;
        const double rho = r(theta);
        pts.push_back({centre.x + rho * std::cos(theta), centre.y + rho * std::sin(theta)});
    }
    return pts;
}

std::vector<Vec2> circle(Vec2 centre, double r, int n, double phase) {
    if (!(r > 0.0)) throw InvalidInput(fmt::format("circle radius must be positive, got {}", r));
    return polar(
        centre, [r](double) { return r; }, n, phase);
}

std::vector<Vec2> propeller(int n, Vec2 centre, double r0, double a, double phase) {
    if (!(r0 > 0.0) || !(std::abs(a) < 1.0)) {
        throw InvalidInput(
            fmt::format("propeller needs r0 > 0 and |a| < 1, got r0 = {}, a = {}", r0, a));
    }
    return polar(
        centre, [=](double t) { return r0 * (1.0 + a * std::cos(3.0 * (t - phase))); }, n, phase);
}

std::vector<Vec2> rectangle(Vec2 lo, Vec2 hi, int per_side) {
    require_count(per_side, 1, "a rectangle side");
    if (!(hi.x > lo.x && hi.y > lo.y))
        throw InvalidInput("rectangle needs hi > lo in both coordinates");
    const Vec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
    std::vector<Vec2> pts;
    for (int s = 0; s < 4; ++s) {
        const Vec2 a = corners[s], b = corners[(s + 1) % 4];
        for (int k = 0; k < per_side; ++k)
            pts.push_back(a + (static_cast<double>(k) / per_side) * (b - a));
    }
    return pts;
}

}  // namespace slc::shapes
