// Tests of the local uniform mesh (paper §3.2, Fig. 9): exactly the lattice points within range of
// Γ, rows and columns describing the same points, size linear in length/h (never M²), and the
// differences and interpolation along its intervals.
#include "slc/geometry_modules/local_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "random_interfaces.hpp"
#include "slc/core/error.hpp"
#include "slc/geometry/shapes.hpp"

namespace slc {
namespace {

/// Lattice points closer than this (in lattice steps) to the boundary of the band are skipped by
/// the brute-force comparison: there membership is decided by rounding and by lattice_slack.
constexpr double boundary_margin = 1e-6;
/// Polynomial data is differentiated and interpolated exactly up to rounding of values ~1.
constexpr double polynomial_tolerance = 1e-9;

/// L∞ distance from p to segment s: f(t) = max(|a.x + t d.x − p.x|, |a.y + t d.y − p.y|) is convex
/// and piecewise linear in t, so its minimum on [0, 1] is at an end or a breakpoint.
double linf_distance(Segment s, Vec2 p) {
    const Vec2 a = s.a - p, d = s.b - s.a;
    auto f = [&](double t) { return std::max(std::abs(a.x + t * d.x), std::abs(a.y + t * d.y)); };
    double best = std::min(f(0.0), f(1.0));
    auto consider = [&](double num, double den) {
        if (den != 0.0 && num / den > 0.0 && num / den < 1.0) best = std::min(best, f(num / den));
    };
    consider(-a.x, d.x);
    consider(-a.y, d.y);
    consider(-(a.x - a.y), d.x - d.y);
    consider(-(a.x + a.y), d.x + d.y);
    return best;
}

TEST(LocalMesh, HoldsExactlyTheLatticePointsWithinRangeOfTheCurve) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const double h = 2.0 / 64;
        const int range = 1 + static_cast<int>(seed % 3);
        const Vec2 origin{-1.0, -1.0};
        const LocalMesh mesh(curves, origin, h, range);
        std::size_t inside = 0;
        for (std::int32_t j = -range - 2; j <= 64 + range + 2; ++j) {
            for (std::int32_t i = -range - 2; i <= 64 + range + 2; ++i) {
                const Vec2 p = mesh.position(i, j);
                double d = 1e300;
                for (std::size_t s = 0; s < curves.size(); ++s)
                    d = std::min(d, linf_distance(curves.segment(s), p));
                const double steps = d / h;
                if (std::abs(steps - range) < boundary_margin) continue;
                EXPECT_EQ(mesh.find(i, j).has_value(), steps < range)
                    << "lattice point " << i << ", " << j;
                inside += steps < range ? 1 : 0;
            }
        }
        EXPECT_GE(mesh.size(), inside);
    }
}

TEST(LocalMesh, RowsAndColumnsListTheSamePointsInOrder) {
    std::mt19937 rng(7);
    const Interface curves = testing::random_interface(rng);
    const LocalMesh mesh(curves, {-1.0, -1.0}, 2.0 / 128, 3);
    const auto rows = mesh.rows();
    std::uint32_t next = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        EXPECT_EQ(rows[k].first, next);
        next += static_cast<std::uint32_t>(rows[k].size());
        if (k == 0) continue;
        EXPECT_GE(rows[k].line, rows[k - 1].line);
        if (rows[k].line == rows[k - 1].line) {
            EXPECT_GT(rows[k].lo, rows[k - 1].hi + 1);
        }
    }
    EXPECT_EQ(next, mesh.size());
    // Every point once in the column order, each y-interval a run of one column.
    std::vector<int> seen(mesh.size(), 0);
    const auto columns = mesh.columns();
    std::size_t position = 0;
    for (std::size_t k = 0; k < columns.size(); ++k) {
        const auto& c = columns[k];
        EXPECT_EQ(c.first, position);
        if (k > 0) {
            EXPECT_GE(c.line, columns[k - 1].line);
            if (c.line == columns[k - 1].line) {
                EXPECT_GT(c.lo, columns[k - 1].hi + 1);
            }
        }
        for (std::int32_t j = c.lo; j <= c.hi; ++j, ++position) {
            const std::uint32_t p = mesh.column_order()[position];
            ++seen[p];
            EXPECT_EQ(mesh.find(c.line, j), std::optional<std::size_t>(p));
        }
    }
    EXPECT_EQ(position, mesh.size());
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

std::size_t circle_points(double r, int m) {
    const Interface curves({shapes::circle({0.013, -0.021}, r, 2000)});
    return LocalMesh(curves, {-1.0, -1.0}, 2.0 / m, 3).size();
}

TEST(LocalMesh, PointCountGrowsWithLengthOverHNotWithMSquared) {
    // A band of half-width R about a curve of length L holds about 2R·L/h points (a little more
    // for the L∞ band of slanted pieces): doubling L or halving h doubles the count. Allowed
    // drift from exactly 2: the band's ends and the circle's curvature change the count by a
    // few percent at these sizes.
    constexpr double ratio_tolerance = 0.06;
    for (const double r : {0.2, 0.4}) {
        const double ratio = static_cast<double>(circle_points(2 * r, 512)) /
                             static_cast<double>(circle_points(r, 512));
        EXPECT_NEAR(ratio, 2.0, 2.0 * ratio_tolerance) << "radius " << r;
    }
    for (const int m : {128, 256, 512, 1024}) {
        const double ratio = static_cast<double>(circle_points(0.5, 2 * m)) /
                             static_cast<double>(circle_points(0.5, m));
        std::printf("M = %d -> %d: local mesh points grow by %.3f (M² grows by 4)\n", m, 2 * m,
                    ratio);
        EXPECT_NEAR(ratio, 2.0, 2.0 * ratio_tolerance) << "M = " << m;
    }
    // And the count is a small multiple of length/h: (2R + 1)·√2 bounds the band's width.
    const double per_length =
        static_cast<double>(circle_points(0.5, 1024)) / (2 * std::numbers::pi * 0.5 / (2.0 / 1024));
    EXPECT_GT(per_length, 2 * 3);
    EXPECT_LT(per_length, (2 * 3 + 1) * std::numbers::sqrt2);
}

TEST(LocalMesh, DifferencesAlongRowsAndColumnsAreExactForPolynomials) {
    const Interface curves({shapes::propeller(300)});
    const LocalMesh mesh(curves, {-1.0, -1.0}, 2.0 / 64, 3);
    const auto pts = mesh.points();
    std::vector<double> f(pts.size());
    auto g = [](Vec2 p) { return 0.3 + p.x - 2 * p.y + p.x * p.x * p.y - 0.5 * p.y * p.y * p.y; };
    for (std::size_t k = 0; k < pts.size(); ++k) f[k] = g(pts[k]);
    const auto fx = derivative(mesh, f, Axis::x, 3), fy = derivative(mesh, f, Axis::y, 3);
    for (std::size_t k = 0; k < pts.size(); ++k) {
        const Vec2 p = pts[k];
        ASSERT_NEAR(fx[k], 1 + 2 * p.x * p.y, polynomial_tolerance);
        ASSERT_NEAR(fy[k], -2 + p.x * p.x - 1.5 * p.y * p.y, polynomial_tolerance);
    }
    // Smoothing keeps linear data (also at interval ends, which it leaves alone).
    for (std::size_t k = 0; k < pts.size(); ++k) f[k] = 1 + 2 * pts[k].x - pts[k].y;
    const auto s = smoothed(mesh, f, 3);
    for (std::size_t k = 0; k < pts.size(); ++k) ASSERT_NEAR(s[k], f[k], polynomial_tolerance);
}

TEST(LocalMesh, InterpolationReproducesPolynomialsAtTheVertices) {
    const Interface curves({shapes::propeller(300)});
    const LocalMesh mesh(curves, {-1.0, -1.0}, 2.0 / 64, 3);
    const auto pts = mesh.points();
    auto g = [](Vec2 p) { return 0.3 + p.x * p.x * p.x - p.x * p.y * p.y + 2 * p.y; };
    std::vector<double> f(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) f[k] = g(pts[k]);
    for (const Vec2 v : curves.points()) {
        const auto value = interpolate(mesh, f, v, 3);
        ASSERT_TRUE(value.has_value());
        EXPECT_NEAR(*value, g(v), polynomial_tolerance);
    }
    EXPECT_FALSE(interpolate(mesh, f, {0.95, 0.95}, 3).has_value());  // far from Γ
}

TEST(LocalMesh, SeveralFieldsAndTheCellCacheGiveTheSingleFieldValues) {
    // Rough data, so that the ENO stencils differ from field to field and cell to cell; a fine
    // curve, so that consecutive vertices share lattice cells and the cache is reused.
    const Interface curves({shapes::propeller(2000)});
    const LocalMesh mesh(curves, {-1.0, -1.0}, 2.0 / 64, 3);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<std::vector<double>> data(5, std::vector<double>(mesh.size()));
    for (auto& field : data)
        for (double& v : field) v = u(rng);
    const std::vector<std::span<const double>> fields(data.begin(), data.end());
    for (const std::size_t count : {std::size_t{3}, std::size_t{5}}) {  // 5: beyond the cache
        const auto some = std::span(fields).first(count);
        CellStencils cell;
        std::vector<Vec2> points(curves.points().begin(), curves.points().end());
        points.insert(points.begin() + 100, Vec2{0.95, 0.95});  // off the mesh, mid-way
        for (const Vec2 p : points) {
            std::vector<double> out(count);
            const bool found = interpolate(mesh, some, p, 3, out, &cell);
            for (std::size_t f = 0; f < count; ++f) {
                const auto single = interpolate(mesh, some[f], p, 3);
                ASSERT_EQ(found, single.has_value());
                if (found) {
                    ASSERT_EQ(out[f], *single);  // bit for bit
                }
            }
        }
    }
}

TEST(LocalMesh, RejectsBadInput) {
    const Interface curves({shapes::circle({}, 0.5, 16)});
    EXPECT_THROW(LocalMesh(Interface(), {}, 0.1, 2), InvalidInput);
    EXPECT_THROW(LocalMesh(curves, {}, 0.0, 2), InvalidInput);
    EXPECT_THROW(LocalMesh(curves, {}, std::nan(""), 2), InvalidInput);
    EXPECT_THROW(LocalMesh(curves, {}, 0.1, 0), InvalidInput);
    EXPECT_THROW(LocalMesh(curves, {}, 1e-12, 2), InvalidInput);  // lattice indices beyond 2^30
}

}  // namespace
}  // namespace slc
