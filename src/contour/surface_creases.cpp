// Cutting a contour along the creases of its zero set (§2.2 in space, for G the distance of a
// surface of flat facets): where a triangle's corners lie on different planes of the zero set,
// the triangle is cut on the line where the planes meet, so that each child lies in one plane.
// Halving the edges across a crease only halves their error; cutting on it leaves none.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "slc/core/key_map.hpp"
#include "slc/core/vec2.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "surface_stages.hpp"

namespace slc::contouring {
namespace {

constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// G's gradient at a vertex is taken by differences this many times its shortest edge (among
/// the triangles cut) away, and at least `min_step` times the vertex's size (1 + its largest
/// coordinate), far above G's rounding.
constexpr double step_fraction = 1e-3;
constexpr double min_step = 1e-8;
/// The one-sided differences agree within this where G is a plane's distance about the vertex:
/// a crease within the step differs by the fold's angle, a surface curved at radius R by the
/// step over R.
constexpr double kink = 1e-3;
/// Two planes are one when their normals agree within this (1 − cos: 1.4e−4 radians) and their
/// offsets within this times their size (1 + |c|).
constexpr double same_cosine = 1.0 - 1e-8;
constexpr double same_offset = 1e-8;
/// An edge is cut only where it crosses the crease at least this steeply (the sine), seen along
/// the planes' mean normal. Where it crosses nearer an end than this fraction of its length, the
/// end is moved onto the crease instead (a cut there would leave a needle).
constexpr double min_crossing_sine = 1e-9;
constexpr double snap_fraction = 0.05;
/// A corner's planes meet at a point when the determinant of their normals is at least this.
constexpr double min_corner_determinant = 1e-3;
/// A child's normal is within this cosine of its plane's (about 25°): a fold turns it over.
constexpr double min_plane_cosine = 0.9;
/// A patch re-triangulated across a crease holds at most this many triangles that lie across it.
constexpr std::size_t max_fold = 512;
/// ... grown by at most this many rings of triangles around it.
constexpr int max_rings = 6;
/// A child that lies in no one plane turns at most 60° from its parent.
constexpr double min_parent_cosine = 0.5;

bool same_plane(const CreasePlane& a, const CreasePlane& b) {
    return dot(a.n, b.n) > same_cosine &&
           std::abs(a.c - b.c) <= same_offset * (1.0 + std::max(std::abs(a.c), std::abs(b.c)));
}

/// The planes of a vertex, as a span.
std::span<const CreasePlane> planes_of(const CreasePlanes& p, std::uint32_t v) {
    return {p.planes[v].data(), p.count[v]};
}

/// Distinct planes, in the order met: those of up to three corners of four planes each.
struct PlaneSet {
    std::array<CreasePlane, 12> planes;
    int size = 0;

    /// Adds p unless a plane already in is the same, and unless `most` are in.
    void add(const CreasePlane& p, int most = 12) {
        for (int i = 0; i < size; ++i)
            if (same_plane(planes[i], p)) return;
        if (size < most) planes[size++] = p;
    }
    /// Adds the planes of vertex v.
    void add_corner(const CreasePlanes& all, std::uint32_t v) {
        for (const CreasePlane& p : planes_of(all, v)) add(p);
    }
    /// The first four.
    std::array<CreasePlane, 4> first_four() const {
        return {planes[0], planes[1], planes[2], planes[3]};
    }
};

/// Where an edge crosses a crease: the point on the crease, and the fraction of the edge's
/// length from its first end.
struct Crossing {
    Vec3 point;
    double s = 0.0;
};

/// Where the line of planes a and b (a point x0 and the direction d = a.n × b.n) meets the plane
/// through the edge from u to w and the planes' mean normal: the crossing of the edge and the
/// crease, seen along that normal. Nothing when the edge runs along the crease or the crossing is
/// not between its ends.
std::optional<Crossing> crossing(Vec3 u, Vec3 w, const CreasePlane& a, const CreasePlane& b) {
    const Vec3 d = cross(a.n, b.n);
    const double dd = norm2(d);
    const Vec3 mean = a.n + b.n;
    if (dd < 1e-12 || norm2(mean) < 1e-12) return std::nullopt;
    // The line's point nearest u, from the planes' offsets relative to u.
    const double ca = a.c - dot(a.n, u), cb = b.c - dot(b.n, u);
    const Vec3 x0 = u + (ca * cross(b.n, d) + cb * cross(d, a.n)) / dd;
    const Vec3 e = w - u;
    const Vec3 q = cross(e, mean);
    const double qd = dot(q, d);
    if (!(std::abs(qd) >= min_crossing_sine * norm(q) * std::sqrt(dd))) return std::nullopt;
    // The edge crosses the plane of the line and the mean normal at u + s e.
    const Vec3 across = cross(d, mean);
    const double s = dot(x0 - u, across) / dot(e, across);
    if (!(s > 0.0 && s < 1.0)) return std::nullopt;
    return Crossing{x0 + (dot(q, u - x0) / qd) * d, s};
}

/// The point of the line of planes a and b nearest x.
Vec3 onto_crease(Vec3 x, const CreasePlane& a, const CreasePlane& b) {
    const Vec3 d = cross(a.n, b.n);
    const double ca = a.c - dot(a.n, x), cb = b.c - dot(b.n, x);
    return x + (ca * cross(b.n, d) + cb * cross(d, a.n)) / norm2(d);
}

/// Where three planes meet, when they meet at a point.
std::optional<Vec3> corner(const std::array<CreasePlane, 3>& p, Vec3 near) {
    const Vec3 bc = cross(p[1].n, p[2].n), ca = cross(p[2].n, p[0].n), ab = cross(p[0].n, p[1].n);
    const double det = dot(p[0].n, bc);
    if (!(std::abs(det) >= min_corner_determinant)) return std::nullopt;
    const double c0 = p[0].c - dot(p[0].n, near), c1 = p[1].c - dot(p[1].n, near),
                 c2 = p[2].c - dot(p[2].n, near);
    return near + (c0 * bc + c1 * ca + c2 * ab) / det;
}

/// Whether x, projected along n onto the plane of triangle (a, b, c), lies inside it.
bool inside(Vec3 x, Vec3 a, Vec3 b, Vec3 c, Vec3 n) {
    const double ab = dot(cross(b - a, x - a), n), bc = dot(cross(c - b, x - b), n),
                 ca = dot(cross(a - c, x - c), n);
    return ab > 0.0 && bc > 0.0 && ca > 0.0;
}

/// Whether the triangle with corners a, b, c has area beyond rounding: twice its area above
/// 1e−9 times its longest edge squared (a needle or a cap of coincident corners has not).
bool has_area(Vec3 a, Vec3 b, Vec3 c) {
    const double longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
    return norm(cross(b - a, c - a)) > 1e-9 * longest * longest;
}

/// The plane that all three corners of triangle t lie on, if any.
std::optional<CreasePlane> common_plane(const CreasePlanes& planes, const TriangleIndices& t) {
    for (const CreasePlane& p : planes_of(planes, t[0])) {
        bool shared = true;
        for (int k = 1; k < 3 && shared; ++k) {
            bool on = false;
            for (const CreasePlane& q : planes_of(planes, t[k])) on = on || same_plane(p, q);
            shared = on;
        }
        if (shared) return p;
    }
    return std::nullopt;
}

/// The number of distinct planes at the corners of triangle t (5 when more than four, or a
/// corner has none).
int plane_count(const CreasePlanes& planes, const TriangleIndices& t) {
    PlaneSet set;
    for (const std::uint32_t u : t) {
        if (planes.count[u] == 0) return 5;
        set.add_corner(planes, u);
    }
    return std::min(set.size, 5);
}

/// Whether triangle t has area, lies in a plane of its three corners and faces as it does.
bool on_its_plane(const Surface& s, const CreasePlanes& planes, const TriangleIndices& t) {
    const std::optional<CreasePlane> p = common_plane(planes, t);
    const Vec3 n = area_normal(s, t);
    return p && has_area(s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]]) &&
           dot(n, p->n) >= min_plane_cosine * norm(n);
}

/// Whether triangle t faces the way its corners' planes do: within about 60° of their distinct
/// normals' mean (a triangle across a crease, toward the crease's bisector), where every corner
/// has a plane. A fold of the contour stands across the crease or faces against it.
bool facing(const Surface& s, const CreasePlanes& planes, const TriangleIndices& t) {
    PlaneSet set;
    for (const std::uint32_t u : t) {
        if (planes.count[u] == 0) return true;  // unknown: not judged
        set.add_corner(planes, u);
    }
    Vec3 mean{0, 0, 0};
    for (int i = 0; i < set.size; ++i) mean = mean + set.planes[i].n;
    const Vec3 n = area_normal(s, t);
    return norm(n) > 0.0 && dot(n, mean) >= 0.5 * norm(n) * norm(mean);
}

/// A cut on an edge: its point, and the planes it lies on.
struct Cut {
    std::uint64_t key = 0;
    Vec3 point;
    CreasePlane a, b;
    bool alive = false;
    std::uint32_t vertex = none;
};

/// A corner put in a triangle: its point, and its three planes.
struct Centre {
    std::uint32_t triangle = 0;
    Vec3 point;
    std::array<CreasePlane, 3> planes;
    bool alive = false;
    std::uint32_t vertex = none;
};

/// The triangles of a simple polygon (counterclockwise, by ear clipping), as indices into it;
/// nothing when an ear of positive area cannot be found.
std::optional<std::vector<std::array<std::uint32_t, 3>>> ear_clip(std::span<const Vec2> p) {
    std::vector<std::uint32_t> left(p.size());
    for (std::uint32_t i = 0; i < p.size(); ++i) left[i] = i;
    double size = 0.0;
    for (const Vec2 q : p) size = std::max({size, std::abs(q.x - p[0].x), std::abs(q.y - p[0].y)});
    const double tiny = 1e-14 * size * size;
    auto area = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        return cross(p[b] - p[a], p[c] - p[a]);
    };
    std::vector<std::array<std::uint32_t, 3>> out;
    while (left.size() > 3) {
        bool found = false;
        const std::size_t m = left.size();
        for (std::size_t i = 0; i < m && !found; ++i) {
            const std::uint32_t a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
            // Convex, and not a straight angle (sine above 1e−9).
            if (!(area(a, b, c) >
                  std::max(tiny, 1e-9 * std::sqrt(norm2(p[b] - p[a]) * norm2(p[c] - p[b])))))
                continue;
            bool empty = true;
            for (const std::uint32_t v : left) {
                if (v == a || v == b || v == c) continue;
                empty = empty &&
                        !(area(a, b, v) >= 0.0 && area(b, c, v) >= 0.0 && area(c, a, v) >= 0.0);
            }
            if (!empty) continue;
            out.push_back({a, b, c});
            left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
            found = true;
        }
        if (!found) return std::nullopt;
    }
    if (!(area(left[0], left[1], left[2]) > tiny)) return std::nullopt;
    out.push_back({left[0], left[1], left[2]});
    return out;
}

/// The triangles that replace a patch of triangles across one crease, or nothing. The patch
/// must be a disk whose boundary corners all lie on the crease's two planes, crossing from one
/// to the other only at corners on both (on the crease); seen along the planes' mean normal,
/// its boundary then splits at those two corners into a polygon on each plane, sharing the
/// segment of the crease between them, and each is triangulated in its plane.
/// A patch re-triangulated: its triangles, where `corner_vertex` stands for the corner the
/// planes meet at when they are more than two (`corner`, a new vertex on all of them).
struct Remeshed {
    std::vector<TriangleIndices> triangles;
    std::optional<Vec3> corner;
    std::array<CreasePlane, 4> planes;
    int count = 0;
};
constexpr std::uint32_t corner_vertex = none - 1;

/// across_creases() where three or four planes meet at a corner: seen along their mean normal,
/// the boundary runs once around the corner, on each plane in turn, from one corner on a crease
/// to the next; each run and the corner are triangulated in the run's plane.
std::optional<Remeshed> around_corner(const Surface& s, const CreasePlanes& planes,
                                      std::span<const std::uint32_t> loop,
                                      const std::array<CreasePlane, 4>& list, int found) {
    const std::optional<Vec3> q = corner({list[0], list[1], list[2]}, s.vertices[loop[0]]);
    if (!q) return std::nullopt;
    for (int i = 3; i < found; ++i) {
        if (!(std::abs(dot(list[i].n, *q) - list[i].c) <=
              same_offset * (1.0 + std::abs(list[i].c))))
            return std::nullopt;
    }
    const std::size_t m = loop.size();
    std::vector<unsigned> mask(m, 0);
    for (std::size_t i = 0; i < m; ++i) {
        for (const CreasePlane& p : planes_of(planes, loop[i]))
            for (int j = 0; j < found; ++j)
                if (same_plane(p, list[j])) mask[i] |= 1u << j;
        if (std::popcount(mask[i]) > 2) return std::nullopt;
    }
    for (std::size_t i = 0; i < m; ++i)
        if ((mask[i] & mask[(i + 1) % m]) == 0) return std::nullopt;
    auto single = [&](std::size_t i) {
        return std::popcount(mask[i]) == 1 ? std::countr_zero(mask[i]) : -1;
    };
    Vec3 mean{0, 0, 0};
    for (int j = 0; j < found; ++j) mean = mean + list[j].n;
    if (norm2(mean) < 1e-12) return std::nullopt;
    const Vec3 axis = mean / norm(mean);
    const Vec3 e1 =
        std::abs(axis.x) < 0.9 ? cross(axis, Vec3{1, 0, 0}) : cross(axis, Vec3{0, 1, 0});
    const Vec3 u = e1 / norm(e1), v = cross(axis, u);
    auto flat = [&](Vec3 x) { return Vec2{dot(x - *q, u), dot(x - *q, v)}; };
    // The corners on one plane only, in boundary order, grouped by plane: each plane once. A
    // group runs from its first such corner to its last (corners on a crease of that plane may
    // lie between); between two groups lie corners on the crease of their two planes only.
    std::size_t begin = m;  // a corner on one plane that starts its group
    for (std::size_t i = 0; i < m && begin == m; ++i) {
        if (single(i) < 0) continue;
        std::size_t k = (i + m - 1) % m;
        while (single(k) < 0 && k != i) k = (k + m - 1) % m;
        if (single(k) != single(i)) begin = i;
    }
    if (begin == m) return std::nullopt;
    struct Group {
        int plane;
        std::size_t first, last;  // loop indices of its first and last corners on one plane
    };
    std::vector<Group> groups;
    for (std::size_t step = 0; step < m; ++step) {
        const std::size_t i = (begin + step) % m;
        const int p = single(i);
        if (p < 0) continue;
        if (groups.empty() || groups.back().plane != p)
            groups.push_back({p, i, i});
        else
            groups.back().last = i;
    }
    if (static_cast<int>(groups.size()) != found) return std::nullopt;
    unsigned used = 0;
    for (const Group& gr : groups) {
        if ((used >> gr.plane) & 1u) return std::nullopt;
        used |= 1u << gr.plane;
        for (std::size_t i = gr.first; i != gr.last; i = (i + 1) % m)
            if (!((mask[i] >> gr.plane) & 1u)) return std::nullopt;
    }
    // Where the boundary passes from group to group: a corner on their crease; of a run of them
    // along the crease, the one where the run's edges pass to the group on their left (moving
    // away from the corner, the next group's side).
    const std::size_t g_count = groups.size();
    std::vector<std::size_t> split(g_count);  // between group k and k + 1
    for (std::size_t k = 0; k < g_count; ++k) {
        const Group &a = groups[k], &b = groups[(k + 1) % g_count];
        const unsigned both = (1u << a.plane) | (1u << b.plane);
        const std::size_t from = (a.last + 1) % m, to = (b.first + m - 1) % m;
        std::size_t length = 1;
        for (std::size_t i = from;; i = (i + 1) % m) {
            if (mask[i] != both) return std::nullopt;
            if (i == to) break;
            ++length;
        }
        const bool outward =
            norm2(flat(s.vertices[loop[to]])) > norm2(flat(s.vertices[loop[from]]));
        split[k] = length == 1 || outward ? from : to;
    }
    Remeshed out{.triangles = {}, .corner = q, .planes = list, .count = found};
    for (std::size_t k = 0; k < g_count; ++k) {
        const int plane = groups[k].plane;
        std::vector<std::uint32_t> piece;
        for (std::size_t i = split[(k + g_count - 1) % g_count];; i = (i + 1) % m) {
            piece.push_back(loop[i]);
            if (i == split[k]) break;
        }
        std::vector<Vec2> points;
        for (const std::uint32_t w : piece) points.push_back(flat(s.vertices[w]));
        points.push_back(Vec2{0, 0});
        const auto triangles = ear_clip(points);
        if (!triangles) return std::nullopt;
        for (const auto& t : *triangles) {
            std::array<Vec3, 3> x;
            TriangleIndices made;
            for (int c = 0; c < 3; ++c) {
                const bool apex = t[c] == piece.size();
                made[c] = apex ? corner_vertex : piece[t[c]];
                x[c] = apex ? *q : s.vertices[piece[t[c]]];
            }
            const Vec3 n = cross(x[1] - x[0], x[2] - x[0]);
            if (!(has_area(x[0], x[1], x[2]) &&
                  dot(n, list[plane].n) >= min_plane_cosine * norm(n))) {
                return std::nullopt;
            }
            out.triangles.push_back(made);
        }
    }
    if (std::popcount(used) != found) return std::nullopt;
    return out;
}

std::optional<Remeshed> across_creases(const Surface& s, const CreasePlanes& planes,
                                       std::span<const std::uint32_t> patch) {
    // The boundary: the patch's directed edges whose reverse is not in it.
    KeyMap<std::uint32_t> directed;
    directed.reserve(3 * patch.size());
    for (const std::uint32_t t : patch) {
        const TriangleIndices& v = s.triangles[t];
        for (int k = 0; k < 3; ++k) directed.assign(std::uint64_t{v[k]} << 32 | v[(k + 1) % 3], 1);
    }
    KeyMap<std::uint32_t> next;  // boundary vertex → the next one
    std::size_t boundary = 0, vertices = 0;
    KeyMap<std::uint32_t> seen;
    std::uint32_t start = none;
    for (const std::uint32_t t : patch) {
        const TriangleIndices& v = s.triangles[t];
        for (int k = 0; k < 3; ++k) {
            if (seen.try_emplace(v[k], 1).second) ++vertices;
            const std::uint32_t a = v[k], b = v[(k + 1) % 3];
            if (directed.find(std::uint64_t{b} << 32 | a)) continue;
            if (!next.try_emplace(a, b).second) return std::nullopt;  // a pinched boundary
            ++boundary;
            start = a;
        }
    }
    const std::size_t edges = (3 * patch.size() + boundary) / 2;
    if (start == none || vertices + patch.size() != edges + 1) return std::nullopt;  // no disk
    std::vector<std::uint32_t> loop;
    for (std::uint32_t v = start;;) {
        loop.push_back(v);
        v = next.at(v);
        if (v == start) break;
        if (loop.size() > boundary) return std::nullopt;
    }
    if (loop.size() != boundary) return std::nullopt;

    // The two planes, and each boundary corner's side: +1 on the first only, −1 on the second
    // only, 0 on both.
    PlaneSet set;
    for (const std::uint32_t v : loop) {
        if (planes.count[v] == 0) return std::nullopt;
        set.add_corner(planes, v);
        if (set.size > 4) return std::nullopt;
    }
    const int found = set.size;
    const std::array<CreasePlane, 4> two = set.first_four();
    if (found < 2) return std::nullopt;
    if (found > 2) return around_corner(s, planes, loop, two, found);
    std::vector<int> side(loop.size());
    for (std::size_t i = 0; i < loop.size(); ++i) {
        bool first = false, second = false;
        for (const CreasePlane& p : planes_of(planes, loop[i])) {
            first = first || same_plane(p, two[0]);
            second = second || same_plane(p, two[1]);
        }
        side[i] = first && second ? 0 : (first ? 1 : -1);
    }
    // Seen along the mean normal: x along the crease, y across it (0 on it).
    const Vec3 d = cross(two[0].n, two[1].n), mean = two[0].n + two[1].n;
    if (norm2(d) < 1e-12 || norm2(mean) < 1e-12) return std::nullopt;
    const Vec3 along = d / norm(d), up = cross(mean / norm(mean), along);
    const Vec3 origin = s.vertices[loop[0]];
    const double ca = two[0].c - dot(two[0].n, origin), cb = two[1].c - dot(two[1].n, origin);
    const Vec3 x0 = origin + (ca * cross(two[1].n, d) + cb * cross(d, two[0].n)) / norm2(d);
    std::vector<Vec2> flat(loop.size());
    double size = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const Vec3 r = s.vertices[loop[i]] - x0;
        flat[i] = {dot(r, along), dot(r, up)};
        size = std::max({size, std::abs(flat[i].x), std::abs(flat[i].y)});
    }
    // Each side strictly on its own side of the crease, the corners on both on it.
    double first_side = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i)
        if (side[i] == 1) first_side = flat[i].y;
    if (first_side == 0.0) return std::nullopt;
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const double y = flat[i].y * (first_side > 0.0 ? 1.0 : -1.0);
        if (side[i] == 0 ? std::abs(y) > 1e-9 * size : !(side[i] * y > 1e-12 * size))
            return std::nullopt;
    }
    // Exactly two crossings from one side to the other, each through corners on the crease (a
    // run of them, whose edges along the crease belong to the side the patch lies on, to their
    // left): the corner where the boundary is split.
    std::vector<std::size_t> crossings;
    const std::size_t m = loop.size();
    const int up_side = first_side > 0.0 ? 1 : -1;  // the side of +y
    for (std::size_t i = 0; i < m; ++i) {
        const std::size_t after_i = (i + 1) % m;
        if (side[i] != 0 && side[after_i] != 0 && side[i] != side[after_i])
            return std::nullopt;  // an edge across the crease
        if (side[i] == 0 || side[after_i] != 0) continue;
        // A run of corners on the crease from after_i.
        std::size_t last = after_i, count = 1;
        while (side[(last + 1) % m] == 0) {
            last = (last + 1) % m;
            if (++count >= m) return std::nullopt;
        }
        const int before = side[i], after = side[(last + 1) % m];
        if (before == after) continue;
        const double dx = flat[last].x - flat[after_i].x;
        const int left = dx > 0.0 ? up_side : -up_side;
        crossings.push_back(count == 1 || left == after ? after_i : last);
    }
    if (crossings.size() != 2) return std::nullopt;
    std::vector<TriangleIndices> out;
    for (int piece = 0; piece < 2; ++piece) {
        const std::size_t from = crossings[piece], to = crossings[1 - piece];
        std::vector<std::uint32_t> corners;
        std::vector<Vec2> points;
        for (std::size_t i = from;; i = (i + 1) % m) {
            corners.push_back(loop[i]);
            points.push_back(flat[i]);
            if (i == to) break;
        }
        const auto triangles = ear_clip(points);
        if (!triangles) return std::nullopt;
        for (const auto& t : *triangles) {
            const TriangleIndices made{corners[t[0]], corners[t[1]], corners[t[2]]};
            if (!on_its_plane(s, planes, made)) return std::nullopt;
            out.push_back(made);
        }
    }
    return Remeshed{.triangles = std::move(out), .corner = std::nullopt, .planes = two, .count = 2};
}

/// Re-triangulates, in the planes of their crease, the patches of the contour where triangles
/// in `beyond` still lie across a crease once cutting has done what it can (a fold of the linear
/// contour, which no cut can flatten): each connected set of them, grown by the triangles around
/// its corners up to three times until across_creases() takes it. A patch whose triangles
/// would meet the rest of the surface is left. Returns the patches replaced.
template <class Measure>
std::size_t remesh_folds(Surface& s, const SpaceEvaluator& g, double eta, CreasePlanes& planes,
                         std::span<const std::uint32_t> beyond, std::vector<double>& centroid_value,
                         std::vector<std::uint8_t>& dirty, Measure&& measure) {
    const std::size_t n = s.size();
    std::vector<std::uint32_t> first(s.vertices.size() + 1, 0), around(3 * n);
    for (const TriangleIndices& t : s.triangles)
        for (const std::uint32_t v : t) ++first[v + 1];
    for (std::size_t v = 0; v < s.vertices.size(); ++v) first[v + 1] += first[v];
    {
        std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
        for (std::uint32_t t = 0; t < n; ++t)
            for (const std::uint32_t v : s.triangles[t]) around[fill[v]++] = t;
    }
    std::vector<std::uint8_t> bad(n, 0), taken(n, 0);
    for (const std::uint32_t t : beyond) bad[t] = !on_its_plane(s, planes, s.triangles[t]) ? 1 : 0;
    std::vector<std::uint32_t> stamp(n, 0);
    std::uint32_t stamps = 0;
    struct Patch {
        std::vector<std::uint32_t> removed;
        Remeshed made;
        std::uint32_t corner = none;  // the corner's vertex, once added
    };
    std::vector<Patch> patches;
    for (const std::uint32_t t0 : beyond) {
        if (taken[t0] || !bad[t0]) continue;
        ++stamps;
        // The triangles across a crease connected to t0 through their corners, a layer at a
        // time (their corners' planes asked first), up to max_fold triangles on at most four
        // planes (more: a curved surface's facets, not a crease or corner).
        PlaneSet seen;
        auto few_planes = [&](std::uint32_t t) {
            for (const std::uint32_t v : s.triangles[t]) {
                seen.add_corner(planes, v);
                if (seen.size > 4) return false;
            }
            return true;
        };
        std::vector<std::uint32_t> patch{t0};
        stamp[t0] = stamps;
        // The triangles around the corners of patch[from, to) not yet met, met now.
        auto ring = [&](std::size_t from, std::size_t to) {
            std::vector<std::uint32_t> out;
            for (std::size_t i = from; i < to; ++i) {
                for (const std::uint32_t v : s.triangles[patch[i]]) {
                    for (std::uint32_t j = first[v]; j < first[v + 1]; ++j) {
                        const std::uint32_t t = around[j];
                        if (stamp[t] == stamps || taken[t]) continue;
                        stamp[t] = stamps;
                        out.push_back(t);
                    }
                }
            }
            return out;
        };
        bool few = few_planes(t0);
        for (std::size_t done = 0; few && done < patch.size() && patch.size() <= max_fold;) {
            const std::size_t end = patch.size();
            const std::vector<std::uint32_t> layer = ring(done, end);
            done = end;
            measure(std::span<const std::uint32_t>(layer));
            for (const std::uint32_t t : layer) {
                if (!on_its_plane(s, planes, s.triangles[t]))
                    patch.push_back(t), few = few && few_planes(t);
                else
                    stamp[t] = 0;
            }
        }
        if (!few || patch.size() > max_fold) {
            for (const std::uint32_t t : patch) taken[t] = 1;
            continue;
        }
        std::optional<Remeshed> made;
        for (int rings = 0; rings < max_rings && !made; ++rings) {
            const std::vector<std::uint32_t> more = ring(0, patch.size());
            patch.insert(patch.end(), more.begin(), more.end());
            measure(std::span<const std::uint32_t>(patch));
            made = across_creases(s, planes, patch);
        }
        for (const std::uint32_t t : patch) taken[t] = 1;
        if (made) patches.push_back({.removed = patch, .made = std::move(*made)});
    }
    // A corner is kept on the zero set only; it is a new vertex on all its planes.
    std::vector<std::uint8_t> keep(patches.size(), 1);
    {
        std::vector<Vec3> points;
        std::vector<std::uint32_t> which;
        for (std::uint32_t i = 0; i < patches.size(); ++i) {
            if (!patches[i].made.corner) continue;
            points.push_back(*patches[i].made.corner);
            which.push_back(i);
        }
        std::vector<double> values(points.size());
        g(points, values);
        for (std::size_t k = 0; k < which.size(); ++k) {
            Patch& p = patches[which[k]];
            if (!(std::abs(values[k]) <= eta)) {
                keep[which[k]] = 0;
                continue;
            }
            p.corner = static_cast<std::uint32_t>(s.vertices.size());
            s.vertices.push_back(points[k]);
            planes.resize(s.vertices.size());
            planes.planes[p.corner] = p.made.planes;
            planes.count[p.corner] = static_cast<std::uint8_t>(p.made.count);
            planes.measured[p.corner] = 1;
            for (TriangleIndices& t : p.made.triangles)
                for (std::uint32_t& v : t)
                    if (v == corner_vertex) v = p.corner;
        }
    }
    // The surface with every patch replaced; a patch whose triangles meet the rest is put back.
    for (;;) {
        Surface next;
        next.vertices = s.vertices;
        std::vector<std::uint8_t> removed(n, 0);
        for (std::size_t i = 0; i < patches.size(); ++i)
            if (keep[i])
                for (const std::uint32_t t : patches[i].removed) removed[t] = 1;
        std::vector<double> next_centroid;
        std::vector<std::uint8_t> next_dirty;
        std::vector<std::uint32_t> owner;  // the patch of each new triangle
        for (std::uint32_t t = 0; t < n; ++t) {
            if (removed[t]) continue;
            next.triangles.push_back(s.triangles[t]);
            next_centroid.push_back(centroid_value[t]);
            next_dirty.push_back(dirty[t]);
            owner.push_back(none);
        }
        std::size_t kept = 0;
        for (std::uint32_t i = 0; i < patches.size(); ++i) {
            if (!keep[i]) continue;
            ++kept;
            for (const TriangleIndices& t : patches[i].made.triangles) {
                next.triangles.push_back(t);
                next_centroid.push_back(nan);
                next_dirty.push_back(1);
                owner.push_back(i);
            }
        }
        if (kept == 0) return 0;
        const std::vector<TriangleContact> contacts = find_self_intersections(next, next_dirty);
        bool dropped = false;
        for (const TriangleContact& c : contacts) {
            for (const std::uint32_t t : {c.first, c.second}) {
                if (owner[t] != none && keep[owner[t]]) keep[owner[t]] = 0, dropped = true;
            }
        }
        if (dropped) continue;
        if (!contacts.empty()) return 0;  // meetings no patch made: not this stage's to mend
        s.triangles = std::move(next.triangles);
        centroid_value = std::move(next_centroid);
        dirty = std::move(next_dirty);
        return kept;
    }
}

}  // namespace

std::size_t cut_creases(Surface& s, const SpaceEvaluator& g, double eta,
                        std::span<const std::uint32_t> beyond, CreasePlanes& planes,
                        std::vector<double>& centroid_value, std::vector<std::uint8_t>& dirty) {
    const std::size_t old_vertices = s.vertices.size();
    planes.resize(old_vertices);

    std::vector<std::pair<std::uint32_t, Vec3>> moved_from;  // vertices moved, where they were
    std::size_t moves = 0;                                   // of them checked
    // The moves not yet checked: one whose triangles meet the rest of the surface is undone.
    auto check_moves = [&] {
        for (std::size_t first_move = moves; moved_from.size() > first_move;) {
            std::vector<std::uint8_t> moved(s.vertices.size(), 0), around_moved(s.size(), 0);
            for (std::size_t k = first_move; k < moved_from.size(); ++k)
                moved[moved_from[k].first] = 1;
            for (std::uint32_t t = 0; t < s.size(); ++t) {
                const TriangleIndices& v = s.triangles[t];
                around_moved[t] = moved[v[0]] || moved[v[1]] || moved[v[2]];
            }
            // A triangle left (nearly) without area, or meeting the rest of the surface.
            std::vector<std::uint8_t> undo(s.vertices.size(), 0);
            bool any = false;
            for (std::uint32_t t = 0; t < s.size(); ++t) {
                if (!around_moved[t]) continue;
                const Triangle3 x = s.triangle(t);
                if (has_area(x.a, x.b, x.c)) continue;
                for (const std::uint32_t v : s.triangles[t]) undo[v] = moved[v];
                any = true;
            }
            if (!any) {
                const std::vector<TriangleContact> contacts =
                    find_self_intersections(s, around_moved);
                if (contacts.empty()) break;
                for (const TriangleContact& c : contacts)
                    for (const std::uint32_t t : {c.first, c.second})
                        for (const std::uint32_t v : s.triangles[t]) undo[v] = moved[v];
            }
            std::size_t kept = first_move;
            for (std::size_t k = first_move; k < moved_from.size(); ++k) {
                const auto [v, from] = moved_from[k];
                if (!undo[v]) {
                    moved_from[kept++] = moved_from[k];
                    continue;
                }
                s.vertices[v] = from;
                planes.count[v] = 0;
                std::erase(planes.moved, v);
            }
            moved_from.resize(kept);
        }
        moves = moved_from.size();
    };
    // The planes at the corners of `triangles` not yet asked: G's gradient by central
    // differences, kept where the one-sided differences agree.
    auto measure = [&](std::span<const std::uint32_t> triangles) {
        std::vector<std::uint32_t> todo;
        KeyMap<std::uint32_t> slot_of;  // vertex → its place in todo
        for (const std::uint32_t t : triangles) {
            for (const std::uint32_t u : s.triangles[t]) {
                if (planes.measured[u]) continue;
                planes.measured[u] = 1;
                slot_of.assign(u, static_cast<std::uint32_t>(todo.size()));
                todo.push_back(u);
            }
        }
        if (todo.empty()) return;
        std::vector<double> shortest(todo.size(), std::numeric_limits<double>::infinity());
        for (const std::uint32_t t : triangles) {
            const TriangleIndices& v = s.triangles[t];
            for (int k = 0; k < 3; ++k) {
                const double l = distance(s.vertices[v[k]], s.vertices[v[(k + 1) % 3]]);
                for (const std::uint32_t u : {v[k], v[(k + 1) % 3]})
                    if (const std::uint32_t* i = slot_of.find(u))
                        shortest[*i] = std::min(shortest[*i], l);
            }
        }
        std::vector<Vec3> points;
        points.reserve(7 * todo.size());
        std::vector<double> steps(todo.size());
        for (std::size_t i = 0; i < todo.size(); ++i) {
            const Vec3 x = s.vertices[todo[i]];
            const double size = 1.0 + std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
            const double h = std::max(step_fraction * shortest[i], min_step * size);
            steps[i] = h;
            points.push_back(x);
            for (const Vec3 e : {Vec3{h, 0, 0}, Vec3{0, h, 0}, Vec3{0, 0, h}}) {
                points.push_back(x + e);
                points.push_back(x - e);
            }
        }
        std::vector<double> values(points.size());
        g(points, values);
        for (std::size_t i = 0; i < todo.size(); ++i) {
            const double h = steps[i];
            const double at = values[7 * i];
            double gradient[3];
            bool flat = true;
            for (int k = 0; k < 3; ++k) {
                const double up = values[7 * i + 2 * k + 1], down = values[7 * i + 2 * k + 2];
                gradient[k] = (up - down) / (2.0 * h);
                flat = flat && std::abs(up + down - 2.0 * at) / h <= kink;
            }
            const Vec3 n{gradient[0], gradient[1], gradient[2]};
            if (!flat || !(norm(n) > 0.5)) continue;
            const std::uint32_t u = todo[i];
            const Vec3 unit = n / norm(n);
            // G = n · x − c about the vertex, G(x) = at.
            planes.planes[u][0] = {unit, dot(unit, s.vertices[u]) - at / norm(n)};
            planes.count[u] = 1;
        }
        // A corner within its step of a crease takes the planes of its neighbours it lies on
        // (within |G| there and twice the step): one, two on a crease, three at a corner.
        std::vector<PlaneSet> near(todo.size());
        for (const std::uint32_t t : triangles) {
            const TriangleIndices& v = s.triangles[t];
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t* at = slot_of.find(v[k]);
                if (!at || planes.count[v[k]] != 0) continue;
                const std::uint32_t i = *at;
                const Vec3 x = s.vertices[v[k]];
                const double tolerance = std::abs(values[7 * i]) + 2.0 * steps[i];
                for (const int j : {1, 2}) {
                    const std::uint32_t u = v[(k + j) % 3];
                    if (planes.count[u] != 1) continue;
                    const CreasePlane& p = planes.planes[u][0];
                    if (!(std::abs(dot(p.n, x) - p.c) <= tolerance)) continue;
                    near[i].add(p, 4);
                }
            }
        }
        // Such a corner is moved onto its planes (their crease, or where three meet), where the
        // zero set is; the caller forgets what it knew of G about it.
        for (std::size_t i = 0; i < todo.size(); ++i) {
            const int count = near[i].size;
            if (count == 0) continue;
            const std::uint32_t u = todo[i];
            const Vec3 x = s.vertices[u];
            std::optional<Vec3> to;
            const auto& p = near[i].planes;
            if (count == 1) {
                to = x - (dot(p[0].n, x) - p[0].c) * p[0].n;
            } else if (count == 2) {
                if (norm2(cross(p[0].n, p[1].n)) > 1e-12) to = onto_crease(x, p[0], p[1]);
            } else {
                to = corner({p[0], p[1], p[2]}, x);
            }
            if (!to || !(distance(*to, x) <= std::abs(values[7 * i]) + 2.0 * steps[i])) continue;
            moved_from.emplace_back(u, x);
            s.vertices[u] = *to;
            planes.moved.push_back(u);
            planes.planes[u] = near[i].first_four();
            planes.count[u] = static_cast<std::uint8_t>(count);
        }
        check_moves();
    };
    measure(beyond);

    // The cuts: an edge between corners on two planes, and a triangle's corner of three planes;
    // then the same in the triangles across the edges cut, which share them, until no edge is
    // added.
    std::vector<Cut> cuts;
    KeyMap<std::uint32_t> cut_of;  // edge key → its index in cuts
    std::vector<Centre> centres;
    const Edges edges(s);  // the triangles on each side of an edge cut
    std::vector<std::uint8_t> scanned(s.size(), 0);
    std::vector<std::uint32_t> scan(beyond.begin(), beyond.end());
    for (const std::uint32_t t : scan) scanned[t] = 1;
    while (!scan.empty()) {
        measure(scan);
        // A corner that an edge crosses a crease beside is moved onto the crease.
        for (const std::uint32_t t : scan) {
            const TriangleIndices& v = s.triangles[t];
            if (plane_count(planes, v) != 2) continue;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t u = v[k], w = v[(k + 1) % 3];
                if (planes.count[u] != 1 || planes.count[w] != 1) continue;
                const CreasePlane a = planes.planes[u][0], b = planes.planes[w][0];
                if (same_plane(a, b)) continue;
                const std::optional<Crossing> c = crossing(s.vertices[u], s.vertices[w], a, b);
                if (!c || (c->s >= snap_fraction && c->s <= 1.0 - snap_fraction)) continue;
                const std::uint32_t end = c->s < snap_fraction ? u : w;
                const Vec3 to = onto_crease(s.vertices[end], a, b);
                moved_from.emplace_back(end, s.vertices[end]);
                s.vertices[end] = to;
                planes.moved.push_back(end);
                planes.planes[end] = {a, b, CreasePlane{}, CreasePlane{}};
                planes.count[end] = 2;
            }
        }
        check_moves();
        const std::size_t first_cut = cuts.size();
        for (const std::uint32_t t : scan) {
            const TriangleIndices& v = s.triangles[t];
            // Only across one crease: a triangle over several folds of a curved surface's
            // facets is split instead.
            for (int k = 0; k < 3 && plane_count(planes, v) == 2; ++k) {
                const std::uint32_t u = v[k], w = v[(k + 1) % 3];
                if (planes.count[u] != 1 || planes.count[w] != 1) continue;
                const CreasePlane &a = planes.planes[u][0], &b = planes.planes[w][0];
                if (same_plane(a, b)) continue;
                const std::uint64_t key = edge_key(u, w);
                if (cut_of.find(key)) continue;
                // Computed from the lower vertex, so either triangle gets the same point.
                const bool lower = u < w;
                const std::optional<Crossing> c =
                    lower ? crossing(s.vertices[u], s.vertices[w], a, b)
                          : crossing(s.vertices[w], s.vertices[u], b, a);
                if (!c) continue;
                cut_of.assign(key, static_cast<std::uint32_t>(cuts.size()));
                cuts.push_back(
                    {.key = key, .point = c->point, .a = lower ? a : b, .b = lower ? b : a});
            }
            PlaneSet set;
            bool known = true;
            for (const std::uint32_t u : v) {
                known = known && planes.count[u] > 0;
                set.add_corner(planes, u);
            }
            if (!known || set.size != 3) continue;
            const std::array<CreasePlane, 3> distinct{set.planes[0], set.planes[1], set.planes[2]};
            const Triangle3 tri = s.triangle(t);
            const Vec3 centroid = (tri.a + tri.b + tri.c) / 3.0;
            const std::optional<Vec3> q = corner(distinct, centroid);
            const Vec3 normal = cross(tri.b - tri.a, tri.c - tri.a);
            if (!q || !inside(*q, tri.a, tri.b, tri.c, normal)) continue;
            centres.push_back({.triangle = t, .point = *q, .planes = distinct});
        }
        std::vector<std::uint32_t> across;
        for (std::size_t i = first_cut; i < cuts.size(); ++i) {
            const std::uint64_t key = cuts[i].key;
            const std::uint32_t e =
                *edges.find(static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key));
            for (const std::uint32_t t : edges.triangles[e]) {
                if (scanned[t]) continue;
                scanned[t] = 1;
                across.push_back(t);
            }
        }
        std::sort(across.begin(), across.end());
        scan = std::move(across);
    }
    if (cuts.empty() && centres.empty()) {
        const std::size_t patched =
            remesh_folds(s, g, eta, planes, beyond, centroid_value, dirty, measure);
        return patched + moved_from.size();
    }

    // Kept only on the zero set.
    {
        std::vector<Vec3> points;
        for (const Cut& c : cuts) points.push_back(c.point);
        for (const Centre& c : centres) points.push_back(c.point);
        std::vector<double> values(points.size());
        g(points, values);
        for (std::size_t i = 0; i < cuts.size(); ++i) cuts[i].alive = std::abs(values[i]) <= eta;
        for (std::size_t i = 0; i < centres.size(); ++i)
            centres[i].alive = std::abs(values[cuts.size() + i]) <= eta;
    }
    // The new vertices, numbered in the order found.
    for (Cut& c : cuts) {
        if (!c.alive) continue;
        c.vertex = static_cast<std::uint32_t>(s.vertices.size());
        s.vertices.push_back(c.point);
    }
    std::vector<std::uint32_t> centre_of(s.size(), none);
    for (std::uint32_t i = 0; i < centres.size(); ++i) {
        Centre& c = centres[i];
        if (!c.alive) continue;
        c.vertex = static_cast<std::uint32_t>(s.vertices.size());
        s.vertices.push_back(c.point);
        centre_of[c.triangle] = i;
    }
    planes.resize(s.vertices.size());
    for (const Cut& c : cuts) {
        if (!c.alive) continue;
        planes.planes[c.vertex] = {c.a, c.b, CreasePlane{}, CreasePlane{}};
        planes.count[c.vertex] = 2;
        planes.measured[c.vertex] = 1;
    }
    for (const Centre& c : centres) {
        if (!c.alive) continue;
        planes.planes[c.vertex] = {c.planes[0], c.planes[1], c.planes[2], CreasePlane{}};
        planes.count[c.vertex] = 3;
        planes.measured[c.vertex] = 1;
    }

    // Each triangle's cuts: its edges' points and its centre.
    auto cut_on = [&](std::uint32_t u, std::uint32_t w) -> Cut* {
        const std::uint32_t* i = cut_of.find(edge_key(u, w));
        return i && cuts[*i].alive ? &cuts[*i] : nullptr;
    };
    std::vector<std::uint8_t> other_diagonal(s.size(), 0);
    auto children_of = [&](std::uint32_t t, std::vector<TriangleIndices>& out) {
        out.clear();
        const TriangleIndices& v = s.triangles[t];
        std::array<std::uint32_t, 3> w{none, none, none};
        unsigned mask = 0;
        for (int k = 0; k < 3; ++k) {
            if (const Cut* c = cut_on(v[k], v[(k + 1) % 3])) w[k] = c->vertex, mask |= 1u << k;
        }
        const std::uint32_t centre = centre_of[t];
        if (centre == none || !centres[centre].alive) {
            split_children(s, v, mask, w, out, other_diagonal[t] != 0);
            return mask != 0;
        }
        std::array<std::uint32_t, 6> loop{};
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            loop[n++] = v[k];
            if (w[k] != none) loop[n++] = w[k];
        }
        for (int i = 0; i < n; ++i)
            out.push_back({loop[i], loop[(i + 1) % n], centres[centre].vertex});
        return true;
    };
    // A child lies in a plane of all three of its corners, facing as it does; one that lies in
    // none (a triangle still across the crease) turns at most 60° from its parent and faces as
    // its corners' planes do.
    auto sound = [&](std::uint32_t t, const std::vector<TriangleIndices>& kids) {
        const Vec3 parent = area_normal(s, s.triangles[t]);
        for (const TriangleIndices& kid : kids) {
            const Vec3 n = area_normal(s, kid);
            const double length = norm(n);
            if (!has_area(s.vertices[kid[0]], s.vertices[kid[1]], s.vertices[kid[2]])) return false;
            const std::optional<CreasePlane> plane = common_plane(planes, kid);
            if (plane ? dot(n, plane->n) < min_plane_cosine * length
                      : dot(n, parent) < min_parent_cosine * length * norm(parent) ||
                            !facing(s, planes, kid))
                return false;
        }
        return true;
    };
    // Withdraws the cuts of triangle t; whether it had any.
    auto withdraw = [&](std::uint32_t t) {
        bool had = false;
        const TriangleIndices& v = s.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t* i = cut_of.find(edge_key(v[k], v[(k + 1) % 3]));
            if (i) had = had || cuts[*i].alive, cuts[*i].alive = false;
        }
        if (centre_of[t] != none) {
            had = had || centres[centre_of[t]].alive;
            centres[centre_of[t]].alive = false;
        }
        return had;
    };

    Surface next;
    std::vector<std::uint32_t> parent;
    std::vector<std::uint8_t> next_dirty;
    std::vector<TriangleIndices> kids;
    for (;;) {
        bool changed = false;
        for (std::uint32_t t = 0; t < s.size(); ++t) {
            if (!children_of(t, kids) || sound(t, kids)) continue;
            // A quadrilateral whose shorter diagonal folds may have a sound other one.
            if (!other_diagonal[t] && kids.size() == 3) {
                other_diagonal[t] = 1;
                if (children_of(t, kids) && sound(t, kids)) continue;
            }
            withdraw(t);
            changed = true;
        }
        if (changed) continue;
        next.vertices = s.vertices;
        next.triangles.clear();
        parent.clear();
        next_dirty.clear();
        for (std::uint32_t t = 0; t < s.size(); ++t) {
            const bool cut = children_of(t, kids);
            for (const TriangleIndices& kid : kids) {
                next.triangles.push_back(kid);
                parent.push_back(t);
                next_dirty.push_back(cut || dirty[t] ? 1 : 0);
            }
        }
        // The triangles around the vertices moved onto their planes are checked too.
        if (!moved_from.empty()) {
            std::vector<std::uint8_t> moved(s.vertices.size(), 0);
            for (const auto& [u, x] : moved_from) moved[u] = 1;
            for (std::size_t i = 0; i < next.size(); ++i) {
                const TriangleIndices& t = next.triangles[i];
                if (moved[t[0]] || moved[t[1]] || moved[t[2]]) next_dirty[i] = 1;
            }
        }
        const std::vector<TriangleContact> contacts = find_self_intersections(next, next_dirty);
        if (contacts.empty()) break;
        bool withdrawn = false;
        for (const TriangleContact& contact : contacts) {
            withdrawn = withdraw(parent[contact.first]) || withdrawn;
            withdrawn = withdraw(parent[contact.second]) || withdrawn;
        }
        if (withdrawn) continue;
        // Triangles meet that no cut made: the moves. Undone, with every cut of the round.
        for (const auto& [u, x] : moved_from) {
            s.vertices[u] = x;
            planes.count[u] = 0;
        }
        moved_from.clear();
        planes.moved.clear();
        for (Cut& c : cuts) c.alive = false;
        for (Centre& c : centres) c.alive = false;
        for (std::uint32_t t = 0; t < s.size(); ++t) centre_of[t] = none;
        break;
    }

    std::size_t added = 0;
    for (const Cut& c : cuts) added += c.alive ? 1 : 0;
    for (const Centre& c : centres) added += c.alive ? 1 : 0;
    if (added == 0) {
        s.vertices.resize(old_vertices);
        planes.resize(old_vertices);
        const std::size_t patched =
            remesh_folds(s, g, eta, planes, beyond, centroid_value, dirty, measure);
        return patched + moved_from.size();
    }
    // A triangle left whole keeps its centroid's value.
    std::vector<double> next_centroid(next.size(), nan);
    for (std::size_t i = 0; i < next.size(); ++i) {
        if (next.triangles[i] == s.triangles[parent[i]])
            next_centroid[i] = centroid_value[parent[i]];
    }
    s.triangles = std::move(next.triangles);
    centroid_value = std::move(next_centroid);
    dirty = std::move(next_dirty);
    return added + moved_from.size();
}

}  // namespace slc::contouring
