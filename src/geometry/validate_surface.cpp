// Validation of user-given surfaces: coordinates, indices, degeneracy, edge and vertex manifold
// checks, self-intersections, and the orientation of nested components.
#include "slc/geometry/validate_surface.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/geometry/triangle_hierarchy.hpp"

namespace slc {
namespace {

void check_coordinates(const Surface& s) {
    if (s.empty()) throw InvalidInput("surface has no triangles");
    for (std::size_t v = 0; v < s.vertices.size(); ++v) {
        for (int i = 0; i < 3; ++i) {
            const double c = s.vertices[v][i];
            if (!std::isfinite(c))
                throw InvalidInput(fmt::format("vertex {} has a non-finite coordinate", v));
            if (std::abs(c) > tolerance::max_coordinate) {
                throw InvalidInput(fmt::format("vertex {} has a coordinate {} beyond ±{:g}", v, c,
                                               tolerance::max_coordinate));
            }
        }
    }
    for (std::size_t t = 0; t < s.size(); ++t) {
        const TriangleIndices& tri = s.triangles[t];
        for (std::uint32_t v : tri) {
            if (v >= s.vertices.size()) {
                throw InvalidInput(fmt::format("triangle {} refers to vertex {}, but there are {}",
                                               t, v, s.vertices.size()));
            }
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] ||
            is_degenerate(s.triangle(t))) {
            throw InvalidInput(fmt::format("triangle {} is degenerate (zero area)", t));
        }
    }
}

/// Every edge in exactly two triangles, traversed in opposite directions. The buckets hold the
/// edges in the order of their (lower, higher) vertices and each edge's half-edges in the order
/// of their triangles, so the first fault reported is the least edge's.
void check_edges(const Surface& s, const HalfEdgeBuckets& buckets) {
    const auto& halves = buckets.halves;
    for (std::uint32_t u = 0; u + 1 < buckets.start.size(); ++u) {
        for (std::uint32_t i = buckets.start[u]; i < buckets.start[u + 1];) {
            const std::uint32_t v = halves[i].first;
            std::uint32_t j = i;
            while (j < buckets.start[u + 1] && halves[j].first == v) ++j;
            const std::uint32_t h = halves[i].second;
            if (j - i == 1) {
                throw InvalidInput(fmt::format(
                    "triangle {} has an open edge (between vertices {} and {}): the surface is "
                    "not closed",
                    h / 3, u, v));
            }
            if (j - i > 2) {
                throw InvalidInput(fmt::format(
                    "edge between vertices {} and {} is non-manifold: triangles {}, {} and {} "
                    "share it",
                    u, v, h / 3, halves[i + 1].second / 3, halves[i + 2].second / 3));
            }
            const std::uint32_t g = halves[i + 1].second;
            if (s.triangles[h / 3][h % 3] == s.triangles[g / 3][g % 3]) {
                throw InvalidInput(fmt::format(
                    "triangles {} and {} are oriented inconsistently across their edge between "
                    "vertices {} and {}",
                    h / 3, g / 3, u, v));
            }
            i = j;
        }
    }
}

/// The triangles around each vertex form one fan (edges already manifold and consistent).
void check_vertices(const Surface& s, const std::vector<std::array<std::uint32_t, 3>>& neighbours) {
    std::vector<std::uint32_t> corners(s.vertices.size(), 0);
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> first(s.vertices.size(), none);
    for (std::uint32_t t = 0; t < s.size(); ++t) {
        for (std::uint32_t v : s.triangles[t]) {
            ++corners[v];
            if (first[v] == none) first[v] = t;
        }
    }
    for (std::uint32_t v = 0; v < s.vertices.size(); ++v) {
        if (first[v] == none) continue;
        // Walk around v: from a triangle with v at corner k, cross the edge ending at v (corner
        // k − 1 to corner k) into the next triangle of the fan.
        std::uint32_t t = first[v], steps = 0;
        do {
            const TriangleIndices& tri = s.triangles[t];
            const int k = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
            t = neighbours[t][(k + 2) % 3];
            ++steps;
        } while (t != first[v] && steps <= corners[v]);
        if (steps != corners[v]) {
            throw InvalidInput(fmt::format(
                "vertex {} is non-manifold: its {} triangles do not form a single fan (triangle {} "
                "is in one)",
                v, corners[v], first[v]));
        }
    }
}

/// The corners of triangles i and j with their shared vertices first, in the same order, and
/// how many they share.
int arrange_shared(const Surface& s, std::uint32_t i, std::uint32_t j, Triangle3& a, Triangle3& b) {
    TriangleIndices p = s.triangles[i], q = s.triangles[j];
    int shared = 0;
    for (int k = 0; k < 3; ++k) {
        for (int m = shared; m < 3; ++m) {
            if (p[k] == q[m]) {
                std::swap(p[shared], p[k]);
                std::swap(q[shared], q[m]);
                ++shared;
                break;
            }
        }
    }
    a = {s.vertices[p[0]], s.vertices[p[1]], s.vertices[p[2]]};
    b = {s.vertices[q[0]], s.vertices[q[1]], s.vertices[q[2]]};
    return shared;
}

/// det(d, e, f) = d · (e × f) in floating point, and a bound on its error when e and f are
/// differences of input points rounded once: sixteen units of rounding of the terms' absolute
/// sum, twice the bound of Shewchuk's orient3d filter, which rounds its differences the same
/// way. The bound is infinite (nothing settled) when the terms are too small for a bound that
/// does not underflow; a value that overflows compares false with its bound, and settles nothing
/// either.
std::pair<double, double> det_and_bound(Vec3 d, Vec3 e, Vec3 f) {
    const double x = e.y * f.z - e.z * f.y, y = e.z * f.x - e.x * f.z, z = e.x * f.y - e.y * f.x;
    const double det = d.x * x + d.y * y + d.z * z;
    const double sum = std::abs(d.x) * (std::abs(e.y * f.z) + std::abs(e.z * f.y)) +
                       std::abs(d.y) * (std::abs(e.z * f.x) + std::abs(e.x * f.z)) +
                       std::abs(d.z) * (std::abs(e.x * f.y) + std::abs(e.y * f.x));
    constexpr double u = std::numeric_limits<double>::epsilon() / 2.0;
    return {det, sum > 1e-250 ? 16.0 * u * sum : std::numeric_limits<double>::infinity()};
}

/// For each vertex, whether its triangles are certain to meet one another only in the edges and
/// the vertex they share (1), so that no pair of them needs the exact test: they form one closed
/// fan, and seen along one direction d (the sum of their area normals) each is a positively
/// oriented triangle and together they wind once around the vertex (exactly one of them holds a
/// fixed direction r across d, none of whose edges lies along r). Projected along d, two of
/// them then meet only in the vertex, or in their shared edge, and each projects one to one. The
/// signs are decided in floating point where its error bound settles them (det_and_bound); a
/// vertex where one is not settled is left to the exact tests (0), as are vertices with no
/// triangle flagged in `changed`. O(N), on all threads.
std::vector<std::uint8_t> certified_fans(const Surface& s, std::span<const std::uint8_t> changed) {
    const std::size_t nv = s.vertices.size();
    const VertexCorners around = vertex_corners(s);
    std::vector<std::uint8_t> certified(nv, 0);
    parallel_for(nv, [&](std::size_t v) {
        const std::uint32_t first = around.start[v], count = around.start[v + 1] - first;
        if (count < 3 || count > 64) return;
        bool any_changed = false;
        for (std::uint32_t k = 0; k < count; ++k)
            any_changed = any_changed || changed[around.corners[first + k] / 3];
        if (!any_changed) return;
        // Each triangle's corners after v, in its order: v → a → b.
        std::array<std::uint32_t, 64> out{}, in{};
        Vec3 d{};
        const Vec3 p = s.vertices[v];
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t corner = around.corners[first + k];
            const TriangleIndices& tri = s.triangles[corner / 3];
            out[k] = tri[(corner + 1) % 3];
            in[k] = tri[(corner + 2) % 3];
            d += cross(s.vertices[out[k]] - p, s.vertices[in[k]] - p);
        }
        // One closed fan: from each triangle's b to the one triangle whose a it is, round all.
        std::uint32_t k = 0;
        for (std::uint32_t step = 0; step < count; ++step) {
            std::uint32_t next = count;
            for (std::uint32_t j = 0; j < count; ++j) {
                if (out[j] == in[k]) {
                    if (next != count) return;  // two triangles leave along one edge
                    next = j;
                }
            }
            if (next == count || (next == 0) != (step + 1 == count)) return;
            k = next;
        }
        // A direction r across d, along no edge's projection; the one triangle holding it.
        const Vec3 axis =
            std::abs(d.x) <= std::abs(d.y) && std::abs(d.x) <= std::abs(d.z)
                ? Vec3{1.0, 0.0, 0.0}
                : (std::abs(d.y) <= std::abs(d.z) ? Vec3{0.0, 1.0, 0.0} : Vec3{0.0, 0.0, 1.0});
        const Vec3 r = cross(d, axis);
        int holding = 0;
        for (std::uint32_t j = 0; j < count; ++j) {
            const Vec3 e = s.vertices[out[j]] - p, f = s.vertices[in[j]] - p;
            const auto [area, area_bound] = det_and_bound(d, e, f);
            if (!(area > area_bound)) return;
            const auto [to_r, to_r_bound] = det_and_bound(d, e, r);
            const auto [from_r, from_r_bound] = det_and_bound(d, r, f);
            if (!(std::abs(to_r) > to_r_bound) || !(std::abs(from_r) > from_r_bound)) return;
            if (to_r > 0.0 && from_r > 0.0) ++holding;
        }
        if (holding == 1) certified[v] = 1;
    });
    return certified;
}

/// Reverses components whose orientation disagrees with their nesting; returns the notes.
std::vector<std::string> orient_components(
    Surface& s, const std::vector<std::array<std::uint32_t, 3>>& neighbours) {
    const auto label = component_labels(s, neighbours);
    const std::size_t count = *std::max_element(label.begin(), label.end()) + 1;
    // Each component as a surface of its own over the same vertices (moved in and out of one
    // scratch surface, so that the vertices are never copied).
    std::vector<std::vector<TriangleIndices>> parts(count);
    for (std::uint32_t t = 0; t < s.size(); ++t) parts[label[t]].push_back(s.triangles[t]);
    std::vector<TriangleIndices> all = std::move(s.triangles);
    std::vector<Box3> boxes(count);
    std::vector<int> volume_signs(count);
    for (std::size_t c = 0; c < count; ++c) {
        s.triangles = std::move(parts[c]);
        boxes[c] = bounding_box(s);
        volume_signs[c] = volume_sign(s);
        parts[c] = std::move(s.triangles);
    }
    std::vector<int> depth(count, 0);
    for (std::size_t d = 0; d < count; ++d) {
        s.triangles = std::move(parts[d]);
        for (std::size_t c = 0; c < count; ++c) {
            // A component lies wholly inside or wholly outside another (no intersections), so
            // one of its vertices decides; the winding number is ±1 inside and 0 outside.
            const Vec3 probe = s.vertices[parts[c].empty() ? 0 : parts[c][0][0]];
            if (c != d && boxes[d].contains(probe) && std::abs(winding_number(s, probe)) > 0.5)
                ++depth[c];
        }
        parts[d] = std::move(s.triangles);
    }
    s.triangles = std::move(all);
    std::vector<std::string> notes;
    std::vector<std::uint8_t> reverse(count, 0);
    for (std::size_t c = 0; c < count; ++c) {
        const bool outward = volume_signs[c] > 0;
        if (outward == (depth[c] % 2 == 0)) continue;
        reverse[c] = 1;
        const auto first = static_cast<std::size_t>(
            std::find(label.begin(), label.end(), static_cast<std::uint32_t>(c)) - label.begin());
        if (count == 1) {
            notes.emplace_back("the surface was oriented inward; reversed its triangles");
        } else {
            notes.push_back(
                fmt::format("component {} (from triangle {}) was oriented {}; reversed", c, first,
                            outward ? "outward inside an odd number of others" : "inward"));
        }
    }
    for (std::uint32_t t = 0; t < s.size(); ++t)
        if (reverse[label[t]]) std::swap(s.triangles[t][1], s.triangles[t][2]);
    return notes;
}

}  // namespace

std::optional<TriangleContact> find_self_intersection(const Surface& s) {
    return find_self_intersection(s, std::vector<std::uint8_t>(s.size(), 1));
}

std::vector<TriangleContact> find_self_intersections(const Surface& s,
                                                     std::span<const std::uint8_t> changed) {
    SLC_ASSERT(changed.size() == s.size(), "one flag a triangle");
    const auto n = static_cast<std::uint32_t>(s.size());
    // Up to half the triangles flagged, the flagged ones get a hierarchy of their own, and every
    // triangle u looks in it for the flagged triangles v its box meets: the cost of the flagged
    // triangles' pairs, and no hierarchy of the whole surface when few changed (a pair of two
    // flagged triangles is tested from the smaller). Beyond, a hierarchy of all (below). A
    // contact lowers partner[] of its smaller triangle to the larger; the least is kept whatever
    // the order the threads find them in.
    std::vector<std::uint32_t> flagged;
    for (std::uint32_t t = 0; t < n; ++t)
        if (changed[t]) flagged.push_back(t);
    if (flagged.empty()) return {};
    // Past half the triangles flagged, one walk of a hierarchy of them all against itself
    // costs less than a search for every triangle (measured: 20% less at 77% flagged, 45% more
    // at 33%); the pairs of two unflagged triangles it meets are passed over.
    const bool join = 2 * flagged.size() >= n;
    if (join && flagged.size() != n) {
        flagged.resize(n);
        std::iota(flagged.begin(), flagged.end(), 0u);
    }
    std::vector<Triangle3> corners(flagged.size());
    parallel_for(flagged.size(), [&](std::size_t k) { corners[k] = s.triangle(flagged[k]); });
    const TriangleHierarchy hierarchy(corners);
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::atomic<std::uint32_t>> partner(n);
    for (auto& p : partner) p.store(none, std::memory_order_relaxed);
    // Triangles u < v whose boxes meet: lowers partner[u] to v when they overlap.
    auto test = [&](std::uint32_t u, std::uint32_t v) {
        std::atomic<std::uint32_t>& slot = partner[u];
        std::uint32_t least = slot.load(std::memory_order_relaxed);
        if (v >= least) return;
        Triangle3 a, b;
        const int shared = arrange_shared(s, u, v, a, b);
        if (!triangles_overlap(a, b, shared)) return;
        while (v < least && !slot.compare_exchange_weak(least, v, std::memory_order_relaxed)) {
        }
    };
    if (join) {
        // The hierarchy against itself gives each pair once. Nearly every pair is two triangles
        // around a vertex, whose fan certified_fans() settles for all its pairs at once.
        const std::vector<std::uint8_t> certified = certified_fans(s, changed);
        const auto settled = [&](std::uint32_t u, std::uint32_t v) {
            const TriangleIndices& p = s.triangles[u];
            const TriangleIndices& q = s.triangles[v];
            for (const std::uint32_t a : p)
                if (certified[a] && (a == q[0] || a == q[1] || a == q[2])) return true;
            return false;
        };
        hierarchy.for_each_overlapping_pair([&](std::uint32_t u, std::uint32_t v) {
            if ((changed[u] || changed[v]) && !settled(u, v)) test(std::min(u, v), std::max(u, v));
        });
    } else {
        parallel_for(
            n,
            [&](std::size_t i) {
                const auto u = static_cast<std::uint32_t>(i);
                hierarchy.for_each_overlapping(bounding_box(s.triangle(u)), [&](std::uint32_t k) {
                    const std::uint32_t v = flagged[k];
                    if (v == u || (changed[u] && v < u)) return;
                    test(std::min(u, v), std::max(u, v));
                });
            },
            expensive_grain);
    }
    std::vector<TriangleContact> out;
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t p = partner[i].load(std::memory_order_relaxed);
        if (p != none) out.push_back({i, p});
    }
    return out;
}

std::optional<TriangleContact> find_self_intersection(const Surface& s,
                                                      std::span<const std::uint8_t> changed) {
    const std::vector<TriangleContact> all = find_self_intersections(s, changed);
    if (all.empty()) return std::nullopt;
    return all.front();
}

PreparedSurface prepare_surface(Surface raw) {
    check_coordinates(raw);
    const HalfEdgeBuckets buckets = half_edges_by_lower_vertex(raw);
    check_edges(raw, buckets);
    const auto neighbours = triangle_neighbours(raw, buckets);
    check_vertices(raw, neighbours);
    if (const auto contact = find_self_intersection(raw)) {
        throw InvalidInput(
            fmt::format("triangles {} and {} intersect", contact->first, contact->second));
    }
    PreparedSurface out;
    out.notes = orient_components(raw, neighbours);
    out.surface = std::move(raw);
    return out;
}

}  // namespace slc
