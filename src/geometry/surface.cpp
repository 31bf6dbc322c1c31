// Surface measures, adjacency, pseudo-normals and the brute-force signed closest point.
#include "slc/geometry/surface.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/predicates.hpp"

namespace slc {

double area(const Surface& s) {
    double sum = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) sum += area(s.triangle(t));
    return sum;
}

double volume(const Surface& s) {
    // Divergence theorem with the field x/3: V = Σ (a · (b × c)) / 6 over outward triangles. The
    // corners are taken relative to the box centre, which keeps the terms small.
    const Vec3 o = bounding_box(s).center();
    double sum = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        sum += dot(tri.a - o, cross(tri.b - o, tri.c - o));
    }
    return sum / 6.0;
}

int volume_sign(const Surface& s) {
    // Σ (a − o) · ((b − o) × (c − o)) is the exact sum for any o on a closed surface. Each term's
    // error (the differences' roundings, then the determinant's) is within 10 ε times its
    // permanent, and the sum's within (N − 1) ε times the sum of the permanents.
    const Vec3 o = bounding_box(s).center();
    double sum = 0.0, permanents = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        const Vec3 u = tri.a - o, v = tri.b - o, w = tri.c - o;
        sum += dot(u, cross(v, w));
        permanents += std::abs(u.x) * (std::abs(v.y * w.z) + std::abs(v.z * w.y)) +
                      std::abs(u.y) * (std::abs(v.z * w.x) + std::abs(v.x * w.z)) +
                      std::abs(u.z) * (std::abs(v.x * w.y) + std::abs(v.y * w.x));
    }
    constexpr double epsilon = 0x1p-53;
    // Below 2^-800 the products may have lost bits to underflow; beyond the largest double, the
    // sum is meaningless.
    const bool in_range = permanents >= 0x1p-800 && permanents <= 0x1p1000;
    const double bound = (16.0 + static_cast<double>(s.size())) * epsilon * permanents;
    if (in_range && std::abs(sum) > bound) return sum > 0.0 ? 1 : -1;
    return exact_volume_sign(s.vertices, s.triangles);
}

Box3 bounding_box(const Surface& s) {
    Box3 b = Box3::empty();
    for (const TriangleIndices& tri : s.triangles)
        for (std::uint32_t v : tri) b = unite(b, {s.vertices[v], s.vertices[v]});
    return b;
}

HalfEdgeBuckets half_edges_by_lower_vertex(const Surface& s) {
    auto lo_hi = [&](std::size_t h) {
        const std::uint32_t a = s.triangles[h / 3][h % 3], b = s.triangles[h / 3][(h + 1) % 3];
        return std::pair{std::min(a, b), std::max(a, b)};
    };
    Buckets by_lower = counting_sort(3 * s.size(), s.vertices.size(),
                                     [&](std::size_t h) { return lo_hi(h).first; });
    HalfEdgeBuckets out;
    out.start = std::move(by_lower.start);
    out.halves.resize(by_lower.items.size());
    parallel_for(s.vertices.size(), [&](std::size_t v) {
        const auto first = out.halves.begin() + out.start[v],
                   last = out.halves.begin() + out.start[v + 1];
        for (std::uint32_t i = out.start[v]; i < out.start[v + 1]; ++i)
            out.halves[i] = {lo_hi(by_lower.items[i]).second, by_lower.items[i]};
        std::sort(first, last);
    });
    return out;
}

std::vector<std::array<std::uint32_t, 3>> triangle_neighbours(const Surface& s) {
    return triangle_neighbours(s, half_edges_by_lower_vertex(s));
}

std::vector<std::array<std::uint32_t, 3>> triangle_neighbours(const Surface& s,
                                                              const HalfEdgeBuckets& buckets) {
    // The two half-edges of each edge lie side by side in their bucket: O(N + V) where a global
    // sort would be O(N log N). Each bucket on its own, on all threads: it writes only the
    // slots of its half-edges.
    std::vector<std::array<std::uint32_t, 3>> out(s.size());
    parallel_for(s.vertices.size(), [&](std::size_t v) {
        const auto first = buckets.halves.begin() + buckets.start[v],
                   last = buckets.halves.begin() + buckets.start[v + 1];
        for (auto it = first; it != last; it += 2) {
            SLC_ASSERT(it + 1 != last && it->first == (it + 1)->first,
                       "every edge has two triangles");
            const std::uint32_t h = it->second, g = (it + 1)->second;
            out[h / 3][h % 3] = g / 3;
            out[g / 3][g % 3] = h / 3;
        }
    });
    return out;
}

void drop_unused_vertices(Surface& s) {
    std::vector<std::uint32_t> renumber(s.vertices.size(), 0);
    for (const TriangleIndices& t : s.triangles)
        for (const std::uint32_t v : t) renumber[v] = 1;
    std::uint32_t used = 0;
    for (std::size_t v = 0; v < s.vertices.size(); ++v) {
        if (!renumber[v]) continue;
        s.vertices[used] = s.vertices[v];
        renumber[v] = used++;
    }
    s.vertices.resize(used);
    for (TriangleIndices& t : s.triangles)
        for (std::uint32_t& v : t) v = renumber[v];
}

VertexCorners vertex_corners(const Surface& s) {
    Buckets by_vertex = counting_sort(3 * s.size(), s.vertices.size(),
                                      [&](std::size_t c) { return s.triangles[c / 3][c % 3]; });
    return {std::move(by_vertex.start), std::move(by_vertex.items)};
}

std::vector<std::uint32_t> component_labels(const Surface& s) {
    return component_labels(s, triangle_neighbours(s));
}

std::vector<std::uint32_t> component_labels(
    const Surface& s, const std::vector<std::array<std::uint32_t, 3>>& neighbours) {
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> label(s.size(), none);
    std::uint32_t next = 0;
    std::vector<std::uint32_t> todo;
    for (std::uint32_t seed = 0; seed < s.size(); ++seed) {
        if (label[seed] != none) continue;
        label[seed] = next;
        todo.push_back(seed);
        while (!todo.empty()) {
            const std::uint32_t t = todo.back();
            todo.pop_back();
            for (std::uint32_t n : neighbours[t]) {
                if (label[n] == none) {
                    label[n] = next;
                    todo.push_back(n);
                }
            }
        }
        ++next;
    }
    return label;
}

std::size_t component_count(const Surface& s) {
    const auto label = component_labels(s);
    return label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + 1;
}

long long euler_characteristic(const Surface& s) {
    std::vector<std::uint8_t> used(s.vertices.size(), 0);
    for (const TriangleIndices& t : s.triangles)
        for (std::uint32_t v : t) used[v] = 1;
    const auto v = static_cast<long long>(std::count(used.begin(), used.end(), 1));
    const auto f = static_cast<long long>(s.size());
    return v - 3 * f / 2 + f;
}

long long genus(const Surface& s) {
    const auto label = component_labels(s);
    const std::size_t count = label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + 1;
    // χ_c = V_c − F_c/2 for a closed component; a vertex of a vertex-manifold surface belongs to
    // one component only.
    std::vector<long long> chi(count, 0);
    std::vector<std::uint8_t> seen(s.vertices.size(), 0);
    for (std::size_t t = 0; t < s.size(); ++t) {
        for (std::uint32_t v : s.triangles[t]) {
            if (!seen[v]) chi[label[t]] += 1;
            seen[v] = 1;
        }
    }
    std::vector<long long> faces(count, 0);
    for (std::uint32_t l : label) ++faces[l];
    long long g = 0;
    for (std::size_t c = 0; c < count; ++c) g += (2 - (chi[c] - faces[c] / 2)) / 2;
    return g;
}

namespace {

/// The face and vertex parts of the pseudo-normals.
void face_and_vertex_normals(const Surface& s, PseudoNormals& n) {
    n.face.resize(s.size());
    n.vertex.assign(s.vertices.size(), Vec3{});
    // Each triangle's normal and angles on all threads; then each vertex sums its triangles'
    // angle-weighted normals in triangle order, on all threads, as one loop over the triangles
    // would.
    std::vector<std::array<double, 3>> angle(s.size());
    parallel_for(s.size(), [&](std::size_t t) {
        const Triangle3 tri = s.triangle(t);
        // The angle at each corner by atan2 of |u × v| and u · v (accurate at every size), u and
        // v its two edges: |u × v| is twice the area at every corner.
        const Vec3 ab = tri.b - tri.a, bc = tri.c - tri.b, ca = tri.a - tri.c;
        const Vec3 normal = cross(ab, -ca);
        const double twice_area = norm(normal);
        n.face[t] = normal / twice_area;
        angle[t] = {std::atan2(twice_area, -dot(ab, ca)), std::atan2(twice_area, -dot(bc, ab)),
                    std::atan2(twice_area, -dot(ca, bc))};
    });
    const VertexCorners at = vertex_corners(s);
    parallel_for(s.vertices.size(), [&](std::size_t v) {
        Vec3 sum{};
        for (std::uint32_t i = at.start[v]; i < at.start[v + 1]; ++i) {
            const std::uint32_t c = at.corners[i];
            sum += angle[c / 3][c % 3] * n.face[c / 3];
        }
        n.vertex[v] = sum;
    });
}

}  // namespace

PseudoNormals pseudo_normals(const Surface& s) {
    PseudoNormals n;
    face_and_vertex_normals(s, n);
    n.edge.resize(s.size());
    const auto neighbours = triangle_neighbours(s);
    parallel_for(s.size(), [&](std::size_t t) {
        for (int k = 0; k < 3; ++k) n.edge[t][k] = n.face[t] + n.face[neighbours[t][k]];
    });
    return n;
}

std::vector<Vec3> vertex_pseudo_normals(const Surface& s) {
    PseudoNormals n;
    face_and_vertex_normals(s, n);
    return std::move(n.vertex);
}

int side_of(const Surface& s, const PseudoNormals& normals, std::uint32_t t,
            const FacetPoint& nearest, Vec3 x) {
    Vec3 n = normals.face[t];
    if (nearest.feature == Feature::edge) n = normals.edge[t][nearest.index];
    if (nearest.feature == Feature::vertex) n = normals.vertex[s.triangles[t][nearest.index]];
    return dot(x - nearest.point, n) < 0.0 ? -1 : 1;
}

SurfacePoint signed_closest_point(const Surface& s, const PseudoNormals& normals,
                                  const NearestFacet& best, Vec3 x) {
    const double d = std::sqrt(best.distance2);
    const FacetPoint& p = best.nearest;
    const double signed_d = d == 0.0 ? 0.0 : side_of(s, normals, best.triangle, p, x) * d;
    return {signed_d, p.point, best.triangle, p.weights, p.feature, p.index};
}

SurfacePoint closest_point_brute_force(const Surface& s, const PseudoNormals& normals, Vec3 x) {
    SLC_ASSERT(!s.empty(), "brute force needs a triangle");
    NearestFacet best;
    for (std::uint32_t t = 0; t < s.size(); ++t) best.offer(t, closest_point(s.triangle(t), x));
    return signed_closest_point(s, normals, best, x);
}

double winding_number(const Surface& s, Vec3 x) {
    // Van Oosterom and Strackee: the solid angle of triangle (a, b, c) seen from the origin is
    // 2 atan2(a · (b × c), |a||b||c| + (a · b)|c| + (a · c)|b| + (b · c)|a|).
    double sum = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        const Vec3 a = tri.a - x, b = tri.b - x, c = tri.c - x;
        const double la = norm(a), lb = norm(b), lc = norm(c);
        const double det = dot(a, cross(b, c));
        const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
        sum += 2.0 * std::atan2(det, den);
    }
    return sum / (4.0 * std::numbers::pi);
}

}  // namespace slc
