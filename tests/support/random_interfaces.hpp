// Seeded random interfaces for oracle tests: several disjoint curves, holes, long and very short
// segments and collinear runs, inside [−1, 1]².
#pragma once

#include <algorithm>
#include <numbers>
#include <random>
#include <vector>

#include "slc/geometry/interface.hpp"
#include "slc/geometry/shapes.hpp"

namespace slc::testing {

/// A star-shaped polygon about c with radii in [r_lo, r_hi] at sorted random angles: simple by
/// construction. Angular gaps vary from tiny to nearly π, so segment lengths do too.
inline std::vector<Vec2> random_star(std::mt19937& rng, Vec2 c, double r_lo, double r_hi, int n) {
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::uniform_real_distribution<double> radius(r_lo, r_hi);
    std::vector<double> angles(static_cast<std::size_t>(n));
    for (double& a : angles) a = angle(rng);
    // Star-shaped about c, hence simple, as long as no angular gap reaches π: fill wide gaps.
    for (bool filled = true; filled;) {
        std::sort(angles.begin(), angles.end());
        angles.erase(std::unique(angles.begin(), angles.end()), angles.end());
        filled = false;
        for (std::size_t k = 0; k < angles.size(); ++k) {
            const double next =
                k + 1 < angles.size() ? angles[k + 1] : angles[0] + 2 * std::numbers::pi;
            if (next - angles[k] > 0.9 * std::numbers::pi) {
                angles.push_back(0.5 * (angles[k] + next));
                filled = true;
                break;
            }
        }
    }
    std::vector<Vec2> pts;
    for (double a : angles) {
        const double r = radius(rng);
        pts.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
    }
    return pts;
}

/// Up to four curves in the four quadrant slots of [−1, 1]²: stars (one with a clockwise hole)
/// and a rectangle whose sides are collinear runs of vertices.
inline Interface random_interface(std::mt19937& rng) {
    std::uniform_int_distribution<int> count(3, 40);
    std::uniform_int_distribution<int> kind(0, 3);
    std::uniform_real_distribution<double> radius(0.3, 0.45);
    const Vec2 slots[4] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
    std::vector<std::vector<Vec2>> curves;
    for (const Vec2 c : slots) {
        switch (kind(rng)) {
            case 0:
                break;  // empty slot
            case 1:
                curves.push_back(random_star(rng, c, 0.05, 0.45, count(rng)));
                break;
            case 2: {
                // The outer curve's vertices are at most a quarter turn apart, so its edges stay
                // farther than 0.3 cos(π/4) > 0.2 from the centre and the hole fits inside.
                curves.push_back(shapes::polar(
                    c, [&](double) { return radius(rng); }, 8 + count(rng)));
                auto hole = random_star(rng, c, 0.05, 0.2, count(rng));
                std::reverse(hole.begin(), hole.end());
                if (hole.size() >= 3) curves.push_back(hole);
                break;
            }
            default:
                curves.push_back(
                    shapes::rectangle(c - Vec2{0.4, 0.2}, c + Vec2{0.3, 0.35}, count(rng) % 6 + 1));
        }
    }
    if (curves.empty()) curves.push_back(random_star(rng, {0, 0}, 0.2, 0.9, count(rng)));
    std::erase_if(curves, [](const auto& c) { return c.size() < 3; });
    return Interface(curves);
}

}  // namespace slc::testing
