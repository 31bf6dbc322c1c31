// The distance to a union of discs or balls against the nearest of many sampled boundary points.
#include "slc/geometry/balls.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace slc {
namespace {

constexpr double pi = std::numbers::pi;

template <int dim>
bool covered(const std::vector<Ball<dim>>& balls, PointOf<dim> p, std::size_t own) {
    for (std::size_t j = 0; j < balls.size(); ++j)
        if (j != own && distance(p, balls[j].centre) < balls[j].radius) return true;
    return false;
}

/// The boundary of the union sampled: points of each sphere that no other ball covers.
std::vector<Vec2> boundary_samples(const std::vector<Ball<2>>& balls, int per_circle) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < balls.size(); ++i)
        for (int k = 0; k < per_circle; ++k) {
            const double a = 2 * pi * k / per_circle;
            const Vec2 p = balls[i].centre + balls[i].radius * Vec2{std::cos(a), std::sin(a)};
            if (!covered(balls, p, i)) out.push_back(p);
        }
    return out;
}

std::vector<Vec3> boundary_samples(const std::vector<Ball<3>>& balls, int per_sphere) {
    std::vector<Vec3> out;
    const double golden = pi * (3.0 - std::sqrt(5.0));
    for (std::size_t i = 0; i < balls.size(); ++i)
        for (int k = 0; k < per_sphere; ++k) {  // a Fibonacci lattice
            const double z = 1.0 - (2.0 * k + 1.0) / per_sphere, s = std::sqrt(1.0 - z * z);
            const Vec3 p = balls[i].centre + balls[i].radius * Vec3{s * std::cos(golden * k),
                                                                    s * std::sin(golden * k), z};
            if (!covered(balls, p, i)) out.push_back(p);
        }
    return out;
}

/// For random points near the union: the distance is never more than the nearest sample's (it
/// is a boundary point's) and within the sampling's spacing of it; the sign says inside.
template <int dim>
void expect_matches_samples(const std::vector<Ball<dim>>& balls, int samples, double spacing,
                            PointOf<dim> lo, PointOf<dim> hi) {
    const auto boundary = boundary_samples(balls, samples);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst_gap = 0.0;
    for (int n = 0; n < 300; ++n) {
        PointOf<dim> x = lo;
        x.x += u(rng) * (hi.x - lo.x);
        x.y += u(rng) * (hi.y - lo.y);
        if constexpr (dim == 3) x.z += u(rng) * (hi.z - lo.z);
        double brute = std::numeric_limits<double>::infinity();
        for (const auto& p : boundary) brute = std::min(brute, distance(x, p));
        bool inside = false;
        for (const auto& b : balls) inside = inside || distance(x, b.centre) < b.radius;
        const double d = union_of_balls_distance<dim>(balls, x);
        EXPECT_EQ(d < 0.0, inside) << "at point " << n;
        EXPECT_LE(std::abs(d), brute + 1e-12) << "at point " << n;
        worst_gap = std::max(worst_gap, brute - std::abs(d));
    }
    EXPECT_LT(worst_gap, spacing);
}

TEST(UnionOfBalls, ThreeMergingDiscsMatchTheirSampledBoundary) {
    // The three discs of merging-circles grown by 0.3: an island (a hole) and two cusps.
    const std::vector<Ball<2>> discs{{{-0.6, 0}, 0.7}, {{0.6, 0}, 0.7}, {{0, 0.9}, 0.6}};
    expect_matches_samples<2>(discs, 200000, 3e-5, {-1.5, -1}, {1.5, 1.7});
}

TEST(UnionOfBalls, ThreeMergingBallsMatchTheirSampledBoundary) {
    // Three balls meeting along circles and at corners where all three spheres cross.
    const std::vector<Ball<3>> balls{{{-0.3, 0, 0}, 0.4}, {{0.3, 0, 0}, 0.4}, {{0, 0.45, 0}, 0.35}};
    expect_matches_samples<3>(balls, 400000, 3e-3, {-0.8, -0.5, -0.5}, {0.8, 0.9, 0.5});
}

TEST(UnionOfBalls, InTheCuspTheDistanceIsToTheCornerNotTheHiddenCircle) {
    // Two unit discs 1.6 apart meet at (0, ±0.6). From (0, 0.5) the nearest circle point lies
    // inside the other disc; the boundary's nearest point is the corner, 0.1 away.
    const std::vector<Ball<2>> discs{{{-0.8, 0}, 1.0}, {{0.8, 0}, 1.0}};
    EXPECT_NEAR(union_of_balls_distance<2>(discs, {0, 0.5}), -0.1, 1e-15);
    // Each circle alone would say -(1 - |(0.8, 0.5)|) = -0.0566.
    const std::vector<Ball<3>> balls{{{-0.8, 0, 0}, 1.0}, {{0.8, 0, 0}, 1.0}};
    EXPECT_NEAR(union_of_balls_distance<3>(balls, {0, 0.3, 0.4}), -0.1, 1e-15);
}

TEST(UnionOfBalls, NoBallsIsInfinitelyFar) {
    EXPECT_EQ(union_of_balls_distance<2>({}, {0, 0}), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace slc
