// Normals and mean curvature at the vertices of a surface by local quadric fits; vertex areas.
#include "slc/geometry_modules/surface_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "weighted_mean.hpp"

namespace slc {
namespace {

/// v scaled to unit length.
Vec3 unit(Vec3 v) { return v / norm(v); }

/// An orthonormal pair spanning the plane normal to the unit vector n.
std::pair<Vec3, Vec3> tangent_frame(Vec3 n) {
    const Vec3 a = std::abs(n.x) < 0.6 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    const Vec3 e1 = unit(cross(n, a));
    return {e1, cross(n, e1)};
}

/// Solves the symmetric positive definite 5×5 system A x = b by Cholesky; false when a pivot
/// falls below tiny times the largest diagonal entry (too few or too collinear neighbours).
bool solve_spd(std::array<std::array<double, 5>, 5> a, std::array<double, 5>& b) {
    constexpr int n = 5;
    double largest = 0.0;
    for (int i = 0; i < n; ++i) largest = std::max(largest, a[i][i]);
    for (int j = 0; j < n; ++j) {
        double d = a[j][j];
        for (int k = 0; k < j; ++k) d -= a[j][k] * a[j][k];
        if (!(d > 1e-10 * largest)) return false;
        a[j][j] = std::sqrt(d);
        for (int i = j + 1; i < n; ++i) {
            double s = a[i][j];
            for (int k = 0; k < j; ++k) s -= a[i][k] * a[j][k];
            a[i][j] = s / a[j][j];
        }
    }
    for (int i = 0; i < n; ++i) {
        double s = b[i];
        for (int k = 0; k < i; ++k) s -= a[i][k] * b[k];
        b[i] = s / a[i][i];
    }
    for (int i = n - 1; i >= 0; --i) {
        double s = b[i];
        for (int k = i + 1; k < n; ++k) s -= a[k][i] * b[k];
        b[i] = s / a[i][i];
    }
    return true;
}

/// The vertices within two rings of vertex i, i excluded, in increasing order.
void two_ring(const VertexRings& rings, std::size_t i, std::vector<std::uint32_t>& out) {
    out.clear();
    for (const std::uint32_t j : rings.of(i)) {
        out.push_back(j);
        for (const std::uint32_t k : rings.of(j))
            if (k != i) out.push_back(k);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

/// The curvature of the sphere through the one-ring of p tangent to the plane normal to n:
/// the mean of 2 (q − p)·n / |q − p|² over the neighbours q, doubled.
double one_ring_curvature(const Surface& s, const VertexRings& rings, std::size_t i, Vec3 n) {
    double sum = 0.0;
    const auto ring = rings.of(i);
    for (const std::uint32_t j : ring) {
        const Vec3 d = s.vertices[j] - s.vertices[i];
        sum += 2.0 * dot(d, n) / dot(d, d);
    }
    return ring.empty() ? 0.0 : 2.0 * sum / static_cast<double>(ring.size());
}

/// The Gaussian mean of vertex values c at every vertex: Σ w_j A_j c_j / Σ w_j A_j over the
/// vertices j within 3σ of vertex i (found by a walk along edges from i), w_j = exp(−|x_j −
/// x_i|²/2σ²), A_j the vertex areas. Independent of how the surface is meshed, to O(h²).
std::vector<double> gaussian_mean(const Surface& s, const VertexRings& rings,
                                  const std::vector<double>& c, double sigma) {
    const std::size_t nv = s.vertices.size();
    const std::vector<double> areas = vertex_areas(s);
    const double reach2 = 9.0 * sigma * sigma;
    std::vector<double> out(nv);
    parallel_for(
        nv,
        [&](std::size_t i) {
            thread_local std::vector<std::uint32_t> queue;
            thread_local std::vector<std::uint32_t> seen_at;  // i for the vertices i met so far
            if (seen_at.size() != nv) seen_at.assign(nv, std::numeric_limits<std::uint32_t>::max());
            const Vec3 x = s.vertices[i];
            const auto mark = static_cast<std::uint32_t>(i);
            queue.assign(1, mark);
            seen_at[i] = mark;
            double sum = 0.0, weight = 0.0;
            for (std::size_t q = 0; q < queue.size(); ++q) {
                const std::uint32_t j = queue[q];
                const double d2 = norm2(s.vertices[j] - x);
                const double w = std::exp(-d2 / (2.0 * sigma * sigma)) * areas[j];
                sum += w * c[j];
                weight += w;
                for (const std::uint32_t k : rings.of(j)) {
                    if (seen_at[k] == mark || norm2(s.vertices[k] - x) > reach2) continue;
                    seen_at[k] = mark;
                    queue.push_back(k);
                }
            }
            out[i] = weight > 0.0 ? sum / weight : c[i];
            for (const std::uint32_t j : queue)
                seen_at[j] = std::numeric_limits<std::uint32_t>::max();
        },
        expensive_grain);
    return out;
}

}  // namespace

VertexRings vertex_rings(const Surface& s) {
    const std::size_t nv = s.vertices.size();
    // Each vertex's neighbours from its corners, sorted, each kept once (an edge of a closed
    // surface is met from both its triangles): every vertex on its own, on all threads.
    const VertexCorners around = vertex_corners(s);
    std::vector<std::uint32_t> all(2 * around.corners.size());
    VertexRings r;
    r.start.assign(nv + 1, 0);
    parallel_for(nv, [&](std::size_t v) {
        const auto first = all.begin() + 2 * static_cast<std::ptrdiff_t>(around.start[v]);
        auto out = first;
        for (std::uint32_t i = around.start[v]; i < around.start[v + 1]; ++i) {
            const std::uint32_t c = around.corners[i];
            const TriangleIndices& t = s.triangles[c / 3];
            *out++ = t[(c + 1) % 3];
            *out++ = t[(c + 2) % 3];
        }
        std::sort(first, out);
        r.start[v + 1] = static_cast<std::size_t>(std::unique(first, out) - first);
    });
    for (std::size_t v = 0; v < nv; ++v) r.start[v + 1] += r.start[v];
    r.ring.resize(r.start[nv]);
    parallel_for(nv, [&](std::size_t v) {
        const auto first = all.begin() + 2 * static_cast<std::ptrdiff_t>(around.start[v]);
        std::copy_n(first, r.start[v + 1] - r.start[v], r.ring.begin() + r.start[v]);
    });
    return r;
}

std::vector<Vec3> angle_weighted_normals(const Surface& s) {
    std::vector<Vec3> n = vertex_pseudo_normals(s);
    for (Vec3& v : n) {
        const double len = norm(v);
        if (len > 0.0) v = v / len;
    }
    return n;
}

std::vector<double> vertex_areas(const Surface& s) {
    std::vector<double> w(s.vertices.size(), 0.0);
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        const double a = 0.5 * norm(cross(tri.b - tri.a, tri.c - tri.a)) / 3.0;
        for (const std::uint32_t v : s.triangles[t]) w[v] += a;
    }
    return w;
}

double area_mean(const Surface& s, std::span<const double> g) {
    SLC_ASSERT(g.size() == s.vertices.size() && !g.empty(), "one value per vertex");
    return weighted_mean(g, vertex_areas(s));
}

SurfaceGeometry surface_geometry(const Surface& s, const SurfaceGeometryOptions& options) {
    if (!(options.smoothing >= 0.0) || !std::isfinite(options.smoothing))
        throw InvalidInput("surface geometry: smoothing must be finite and non-negative");
    const std::size_t nv = s.vertices.size();
    SurfaceGeometry g;
    g.normals = angle_weighted_normals(s);
    const VertexRings rings = vertex_rings(s);
    if (options.curvature) g.curvature.assign(nv, 0.0);
    std::vector<Vec3> fitted(g.normals);
    parallel_for(
        nv,
        [&](std::size_t i) {
            if (rings.of(i).empty()) return;  // a vertex no triangle uses
            thread_local std::vector<std::uint32_t> near;
            two_ring(rings, i, near);
            const Vec3 p = s.vertices[i];
            const Vec3 n = g.normals[i];
            const auto [e1, e2] = tangent_frame(n);
            // Coordinates scaled by the mean distance h to the neighbours keep the normal
            // equations well conditioned at any size.
            double h = 0.0;
            for (const std::uint32_t j : near) h += norm(s.vertices[j] - p);
            h /= static_cast<double>(near.size());
            std::array<std::array<double, 5>, 5> a{};
            std::array<double, 5> rhs{};
            for (const std::uint32_t j : near) {
                const Vec3 d = (s.vertices[j] - p) / h;
                const double u = dot(d, e1), v = dot(d, e2), w = dot(d, n);
                const std::array<double, 5> row{u * u, u * v, v * v, u, v};
                const double weight = 1.0 / dot(d, d);
                for (int r = 0; r < 5; ++r) {
                    rhs[r] += weight * row[r] * w;
                    for (int c = 0; c < 5; ++c) a[r][c] += weight * row[r] * row[c];
                }
            }
            if (near.size() < 5 || !solve_spd(a, rhs)) {
                if (options.curvature) g.curvature[i] = one_ring_curvature(s, rings, i, n);
                return;
            }
            // Back to unscaled coordinates: second derivatives gain 1/h, first ones stay.
            const double ca = rhs[0] / h, cb = rhs[1] / h, cc = rhs[2] / h;
            const double cd = rhs[3], ce = rhs[4];
            fitted[i] = unit(n - cd * e1 - ce * e2);
            if (options.curvature) {
                const double q = 1.0 + cd * cd + ce * ce;
                g.curvature[i] =
                    ((1.0 + ce * ce) * 2.0 * ca - 2.0 * cd * ce * cb + (1.0 + cd * cd) * 2.0 * cc) /
                    (q * std::sqrt(q));
            }
        },
        expensive_grain);
    g.normals = std::move(fitted);
    if (options.curvature && options.smoothing > 0.0 && !s.triangles.empty())
        g.curvature = gaussian_mean(s, rings, g.curvature, options.smoothing);
    return g;
}

}  // namespace slc
