// Built-in closed surfaces: icosphere, torus, subdivided box, and their union.
#include "slc/geometry/surface_shapes.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// Reverses every triangle whose normal points against `outward` (a direction per triangle).
template <class Outward>
void orient(Surface& s, Outward&& outward) {
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        const Vec3 n = cross(tri.b - tri.a, tri.c - tri.a);
        if (dot(n, outward(tri)) < 0.0) std::swap(s.triangles[t][1], s.triangles[t][2]);
    }
}

Vec3 centroid(const Triangle3& t) { return (t.a + t.b + t.c) / 3.0; }

}  // namespace

Surface sphere(Vec3 center, double radius, int subdivisions) {
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw InvalidInput(fmt::format("sphere radius must be positive, got {}", radius));
    if (subdivisions < 0 || subdivisions > 10) {
        throw InvalidInput(
            fmt::format("sphere subdivisions must be between 0 and 10, got {}", subdivisions));
    }
    // The icosahedron: the cyclic permutations of (0, ±1, ±φ).
    const double phi = std::numbers::phi;
    std::vector<Vec3> unit = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                              {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                              {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
    for (Vec3& p : unit) p = p / norm(p);
    std::vector<TriangleIndices> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoints.try_emplace(key, 0u);
            if (inserted) {
                const Vec3 m = unit[a] + unit[b];
                it->second = static_cast<std::uint32_t>(unit.size());
                unit.push_back(m / norm(m));
            }
            return it->second;
        };
        std::vector<TriangleIndices> finer;
        finer.reserve(4 * faces.size());
        for (const TriangleIndices& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                                ca = midpoint(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({f[1], bc, ab});
            finer.push_back({f[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = std::move(finer);
    }
    Surface s;
    s.vertices.reserve(unit.size());
    for (const Vec3& p : unit) s.vertices.push_back(center + radius * p);
    s.triangles = std::move(faces);
    orient(s, [&](const Triangle3& t) { return centroid(t) - center; });
    return s;
}

Surface torus(Vec3 center, double major, double minor, int around, int across) {
    if (!(minor > 0.0) || !(major > minor) || !std::isfinite(major)) {
        throw InvalidInput(fmt::format(
            "torus radii must satisfy 0 < minor < major, got major {} and minor {}", major, minor));
    }
    if (around < 3 || across < 3 || around > 100000 || across > 100000) {
        throw InvalidInput(fmt::format("torus needs 3 to 100000 divisions each way, got {} and {}",
                                       around, across));
    }
    Surface s;
    const auto n = static_cast<std::uint32_t>(around), m = static_cast<std::uint32_t>(across);
    for (std::uint32_t i = 0; i < n; ++i) {
        const double u = 2.0 * std::numbers::pi * i / n;
        for (std::uint32_t j = 0; j < m; ++j) {
            const double v = 2.0 * std::numbers::pi * j / m;
            const double r = major + minor * std::cos(v);
            s.vertices.push_back(center +
                                 Vec3{r * std::cos(u), r * std::sin(u), minor * std::sin(v)});
        }
    }
    auto at = [&](std::uint32_t i, std::uint32_t j) { return (i % n) * m + (j % m); };
    for (std::uint32_t i = 0; i < n; ++i) {
        for (std::uint32_t j = 0; j < m; ++j) {
            s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    // Outward: away from the nearest point of the tube's core circle.
    orient(s, [&](const Triangle3& t) {
        const Vec3 p = centroid(t) - center;
        const double rho = std::hypot(p.x, p.y);
        return p - Vec3{major * p.x / rho, major * p.y / rho, 0.0};
    });
    return s;
}

Surface box_surface(Vec3 lo, Vec3 hi, int n) {
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z) || !is_finite(lo) || !is_finite(hi))
        throw InvalidInput("box corners must satisfy lo < hi in every coordinate");
    if (n < 1 || n > 1000)
        throw InvalidInput(fmt::format("box divisions must be between 1 and 1000, got {}", n));
    const auto k = static_cast<std::uint32_t>(n);
    // Lattice points (i, j, l) in [0, n]³ on the boundary get consecutive numbers.
    std::vector<std::uint32_t> index(std::size_t{k + 1} * (k + 1) * (k + 1), 0);
    auto slot = [&](std::uint32_t i, std::uint32_t j, std::uint32_t l) -> std::uint32_t& {
        return index[(std::size_t{i} * (k + 1) + j) * (k + 1) + l];
    };
    Surface s;
    for (std::uint32_t i = 0; i <= k; ++i) {
        for (std::uint32_t j = 0; j <= k; ++j) {
            for (std::uint32_t l = 0; l <= k; ++l) {
                if (i != 0 && i != k && j != 0 && j != k && l != 0 && l != k) continue;
                slot(i, j, l) = static_cast<std::uint32_t>(s.vertices.size());
                auto lerp = [&](double a, double b, std::uint32_t q) {
                    return q == k ? b : a + (b - a) * q / k;
                };
                s.vertices.push_back(
                    {lerp(lo.x, hi.x, i), lerp(lo.y, hi.y, j), lerp(lo.z, hi.z, l)});
            }
        }
    }
    // Each face: axis a fixed at 0 or n, the other two axes running over the grid.
    for (int a = 0; a < 3; ++a) {
        for (std::uint32_t side : {0u, k}) {
            for (std::uint32_t p = 0; p < k; ++p) {
                for (std::uint32_t q = 0; q < k; ++q) {
                    auto v = [&](std::uint32_t dp, std::uint32_t dq) {
                        std::uint32_t c[3];
                        c[a] = side;
                        c[(a + 1) % 3] = p + dp;
                        c[(a + 2) % 3] = q + dq;
                        return slot(c[0], c[1], c[2]);
                    };
                    s.triangles.push_back({v(0, 0), v(1, 0), v(1, 1)});
                    s.triangles.push_back({v(0, 0), v(1, 1), v(0, 1)});
                }
            }
        }
    }
    const Vec3 middle = 0.5 * (lo + hi);
    orient(s, [&](const Triangle3& t) {
        // The axis along which the (flat, axis-aligned) triangle's corners agree.
        Vec3 out{};
        const Vec3 c = centroid(t);
        if (t.a.x == t.b.x && t.b.x == t.c.x) out.x = c.x - middle.x;
        if (t.a.y == t.b.y && t.b.y == t.c.y) out.y = c.y - middle.y;
        if (t.a.z == t.b.z && t.b.z == t.c.z) out.z = c.z - middle.z;
        return out;
    });
    return s;
}

Surface enright_sphere(int subdivisions) { return sphere({0.35, 0.35, 0.35}, 0.15, subdivisions); }

Surface join(const std::vector<Surface>& parts) {
    Surface s;
    for (const Surface& p : parts) {
        const auto offset = static_cast<std::uint32_t>(s.vertices.size());
        s.vertices.insert(s.vertices.end(), p.vertices.begin(), p.vertices.end());
        for (TriangleIndices t : p.triangles) {
            for (std::uint32_t& v : t) v += offset;
            s.triangles.push_back(t);
        }
    }
    return s;
}

}  // namespace slc
