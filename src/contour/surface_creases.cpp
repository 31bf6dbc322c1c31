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
/// ... grown by at most this many rings of triangles around it, or about a corner in as many
/// balls, each 1.5 times as wide, up to this many triangles.
constexpr int max_rings = 6;
constexpr std::size_t max_corner_patch = 16 * max_fold;
/// A child that lies in no one plane turns at most 60° from its parent.
constexpr double min_parent_cosine = 0.5;

bool same_plane(const CreasePlane& a, const CreasePlane& b) {
    return dot(a.n, b.n) > same_cosine &&
           std::abs(a.c - b.c) <= same_offset * (1.0 + std::max(std::abs(a.c), std::abs(b.c)));
}

constexpr int max_planes = CreasePlanes::max_planes;

/// Distinct planes, in the order met, up to max_planes; `size` is one more when more were met.
struct PlaneSet {
    std::array<CreasePlane, max_planes> planes;
    int size = 0;

    /// Adds p unless a plane already in is the same.
    void add(const CreasePlane& p) {
        for (int i = 0; i < std::min(size, max_planes); ++i)
            if (same_plane(planes[i], p)) return;
        if (size < max_planes)
            planes[size++] = p;
        else
            size = max_planes + 1;
    }
    /// Adds the planes of vertex v.
    void add_corner(const CreasePlanes& all, std::uint32_t v) {
        for (const CreasePlane& p : all.of(v)) add(p);
    }
    /// The planes, when no more than max_planes were met.
    std::span<const CreasePlane> list() const {
        return {planes.data(), static_cast<std::size_t>(std::min(size, max_planes))};
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

/// Where the planes of `list` (three or more) all meet, when they meet at a point: that of the
/// first three of them that meet at one, if the others pass through it.
std::optional<Vec3> meeting_point(std::span<const CreasePlane> list, Vec3 near) {
    const std::size_t n = list.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                const std::optional<Vec3> q = corner({list[i], list[j], list[k]}, near);
                if (!q) continue;
                for (const CreasePlane& p : list)
                    if (!(std::abs(dot(p.n, *q) - p.c) <= same_offset * (1.0 + std::abs(p.c))))
                        return std::nullopt;
                return q;
            }
    return std::nullopt;
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
    for (const CreasePlane& p : planes.of(t[0])) {
        bool shared = true;
        for (int k = 1; k < 3 && shared; ++k) {
            bool on = false;
            for (const CreasePlane& q : planes.of(t[k])) on = on || same_plane(p, q);
            shared = on;
        }
        if (shared) return p;
    }
    return std::nullopt;
}

/// The number of distinct planes at the corners of triangle t (max_planes + 1 when more, or a
/// corner has none).
int plane_count(const CreasePlanes& planes, const TriangleIndices& t) {
    PlaneSet set;
    for (const std::uint32_t u : t) {
        if (planes.count[u] == 0) return max_planes + 1;
        set.add_corner(planes, u);
    }
    return set.size;
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
    // Whether b turns by less than a sine of 1e−9 from a to c (a straight angle, or a corner
    // folded back on itself).
    auto straight = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        return !(std::abs(area(a, b, c)) >
                 std::max(tiny, 1e-9 * std::sqrt(norm2(p[b] - p[a]) * norm2(p[c] - p[b]))));
    };
    std::vector<std::array<std::uint32_t, 3>> out;
    while (left.size() > 3) {
        bool found = false;
        const std::size_t m = left.size();
        auto at = [&](std::size_t i) { return left[i % m]; };
        // An ear beside a straight corner first: one clipped elsewhere could leave the straight
        // corner and its two neighbours as a triangle of no area.
        for (int pass = 0; pass < 2 && !found; ++pass) {
            for (std::size_t i = 0; i < m && !found; ++i) {
                const std::uint32_t a = at(i + m - 1), b = at(i), c = at(i + 1);
                if (pass == 0 && !straight(at(i + m - 2), a, b) && !straight(b, c, at(i + 2)))
                    continue;
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
        }
        if (!found) return std::nullopt;
    }
    if (!(area(left[0], left[1], left[2]) > tiny)) return std::nullopt;
    out.push_back({left[0], left[1], left[2]});
    return out;
}

/// A patch re-triangulated: its triangles, where `corner_vertex` stands for the corner the
/// planes meet at when they are more than two (`corner`, a new vertex on all of them) and
/// cut_vertex(k) for the point of `cuts[k]`: a boundary edge cut where it crosses a crease,
/// whose triangle outside the patch is split there too.
struct BoundaryCut {
    std::uint32_t from, to;  ///< the edge, as the patch's boundary runs
    Vec3 point;
    CreasePlane a, b;
};
struct Remeshed {
    std::vector<TriangleIndices> triangles;
    std::optional<Vec3> corner;
    std::vector<CreasePlane> planes;
    std::vector<BoundaryCut> cuts;
};
constexpr std::uint32_t corner_vertex = none - 1;
constexpr std::uint32_t cut_vertex(std::size_t k) {
    return corner_vertex - 1 - static_cast<std::uint32_t>(k);
}

/// across_creases() where three or more planes (up to max_planes) meet at a corner: the
/// boundary runs once around the corner, on each plane in turn, from one corner on a crease to
/// the next; each run and the corner are triangulated in the run's plane, seen along its normal.
/// A boundary edge that crosses a crease (left uncut where its triangles are within ε) is cut
/// there, and the triangle beyond it too.
std::optional<Remeshed> around_corner(const Surface& s, const CreasePlanes& planes,
                                      std::span<const std::uint32_t> boundary,
                                      std::span<const CreasePlane> list) {
    const int found = static_cast<int>(list.size());
    const std::optional<Vec3> q = meeting_point(list, s.vertices[boundary[0]]);
    if (!q) return std::nullopt;
    Remeshed out{.triangles = {}, .corner = q, .planes = {list.begin(), list.end()}, .cuts = {}};
    std::vector<unsigned> on(boundary.size(), 0);  // the planes of each corner, as bits
    for (std::size_t i = 0; i < boundary.size(); ++i) {
        for (const CreasePlane& p : planes.of(boundary[i]))
            for (int j = 0; j < found; ++j)
                if (same_plane(p, list[j])) on[i] |= 1u << j;
        if (std::popcount(on[i]) > 2) return std::nullopt;
    }
    // The boundary with a corner put where an edge between two planes crosses their crease
    // (creases leaving the corner are left uncut where their triangles are within ε).
    std::vector<std::uint32_t> loop;
    std::vector<unsigned> mask;
    std::vector<Vec3> where;
    for (std::size_t i = 0; i < boundary.size(); ++i) {
        const std::size_t j = (i + 1) % boundary.size();
        loop.push_back(boundary[i]);
        mask.push_back(on[i]);
        where.push_back(s.vertices[boundary[i]]);
        if ((on[i] & on[j]) != 0) continue;
        // Of the planes of its ends, the two whose crease the edge crosses nearest its line.
        const std::uint32_t u = boundary[i], w = boundary[j];
        std::optional<Crossing> c;
        unsigned pair = 0;
        double nearest = std::numeric_limits<double>::infinity();
        for (unsigned from = on[i]; from != 0; from &= from - 1) {
            for (unsigned to = on[j]; to != 0; to &= to - 1) {
                const CreasePlane &a = list[std::countr_zero(from)],
                                  &b = list[std::countr_zero(to)];
                // Computed from the lower vertex, as cut_creases does.
                const std::optional<Crossing> here =
                    u < w ? crossing(s.vertices[u], s.vertices[w], a, b)
                          : crossing(s.vertices[w], s.vertices[u], b, a);
                if (!here) continue;
                const Vec3 e = s.vertices[w] - s.vertices[u];
                const double off =
                    norm(cross(here->point - s.vertices[u], e)) / std::max(norm(e), 1e-300);
                if (off < nearest) {
                    nearest = off, c = here;
                    pair = (from & -from) | (to & -to);
                }
            }
        }
        if (!c) return std::nullopt;
        const CreasePlane &a = list[std::countr_zero(pair)], &b = list[31 - std::countl_zero(pair)];
        loop.push_back(cut_vertex(out.cuts.size()));
        mask.push_back(pair);
        where.push_back(c->point);
        out.cuts.push_back({.from = u, .to = w, .point = c->point, .a = a, .b = b});
    }
    const std::size_t m = loop.size();
    // Points of a plane in its own coordinates about the corner, counterclockwise seen from
    // the side its normal points to.
    auto flat_in = [&](const CreasePlane& p) {
        const Vec3 e1 =
            std::abs(p.n.x) < 0.9 ? cross(p.n, Vec3{1, 0, 0}) : cross(p.n, Vec3{0, 1, 0});
        const Vec3 u = e1 / norm(e1), v = cross(p.n, u);
        return [u, v, q = *q](Vec3 x) { return Vec2{dot(x - q, u), dot(x - q, v)}; };
    };
    // Each boundary edge lies on the plane of both its ends; one along a crease (both ends on
    // the same two planes) is given to the plane on the side it runs to: a run of them along a
    // crease away from the corner belongs to the plane after it, towards the corner to the
    // plane before it (either way, its piece with the corner stays simple).
    std::vector<int> plane_of(m, -1);  // edge i, from loop[i] to loop[i + 1]
    for (std::size_t i = 0; i < m; ++i) {
        const unsigned common = mask[i] & mask[(i + 1) % m];
        if (common == 0) return std::nullopt;
        if (std::popcount(common) == 1) plane_of[i] = std::countr_zero(common);
    }
    std::size_t start = m;  // an edge on one plane
    for (std::size_t i = 0; i < m && start == m; ++i)
        if (plane_of[i] >= 0) start = i;
    if (start == m) return std::nullopt;
    for (std::size_t step = 1; step < m; ++step) {
        const std::size_t i = (start + step) % m;
        if (plane_of[i] >= 0) continue;
        std::size_t end = i;  // the run of edges along the crease: [i, end]
        while (plane_of[(end + 1) % m] < 0) end = (end + 1) % m;
        const int before = plane_of[(i + m - 1) % m], after = plane_of[(end + 1) % m];
        const unsigned crease = mask[i] & mask[(i + 1) % m];
        const bool outward = distance(where[(end + 1) % m], *q) > distance(where[i], *q);
        const int to = outward ? after : before;
        if (!((crease >> to) & 1u)) return std::nullopt;
        for (std::size_t k = i;; k = (k + 1) % m) {
            plane_of[k] = to;
            if (k == end) break;
        }
    }
    // The runs of edges on one plane, each plane's one run, each triangulated with the corner
    // in its plane.
    std::size_t first = m;  // the first edge of a run
    for (std::size_t i = 0; i < m && first == m; ++i)
        if (plane_of[i] != plane_of[(i + m - 1) % m]) first = i;
    if (first == m) return std::nullopt;
    unsigned used = 0;
    for (std::size_t step = 0; step < m;) {
        const std::size_t begin = (first + step) % m;
        const int plane = plane_of[begin];
        if ((used >> plane) & 1u) return std::nullopt;
        used |= 1u << plane;
        std::vector<std::size_t> piece{begin};  // places in loop
        while (step < m && plane_of[(first + step) % m] == plane) {
            piece.push_back((first + step + 1) % m);
            ++step;
        }
        std::vector<Vec2> points;
        const auto flat = flat_in(list[plane]);
        for (const std::size_t i : piece) points.push_back(flat(where[i]));
        points.push_back(Vec2{0, 0});
        const auto triangles = ear_clip(points);
        if (!triangles) return std::nullopt;
        for (const auto& t : *triangles) {
            std::array<Vec3, 3> x;
            TriangleIndices made;
            for (int c = 0; c < 3; ++c) {
                const bool apex = t[c] == piece.size();
                made[c] = apex ? corner_vertex : loop[piece[t[c]]];
                x[c] = apex ? *q : where[piece[t[c]]];
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

/// The triangles that replace a patch of triangles across one crease, or nothing
/// (around_corner() where more planes meet). The patch must be a disk whose boundary corners all
/// lie on the crease's two planes (a corner of three or more planes, placed by another patch, on
/// one of them or both), crossing from one to the other only at corners on both (on
/// the crease); seen along the planes' mean normal, its boundary then splits at those two
/// corners into a polygon on each plane, sharing the segment of the crease between them, and
/// each is triangulated in its plane.
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
        if (planes.count[v] >= 3) continue;
        set.add_corner(planes, v);
        if (set.size > max_planes) return std::nullopt;
    }
    const int found = set.size;
    if (found < 2) return std::nullopt;
    if (found > 2) return around_corner(s, planes, loop, set.list());
    const std::span<const CreasePlane> two = set.list();
    std::vector<int> side(loop.size());
    for (std::size_t i = 0; i < loop.size(); ++i) {
        bool first = false, second = false;
        for (const CreasePlane& p : planes.of(loop[i])) {
            first = first || same_plane(p, two[0]);
            second = second || same_plane(p, two[1]);
        }
        if (!first && !second) return std::nullopt;
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
    return Remeshed{.triangles = std::move(out),
                    .corner = std::nullopt,
                    .planes = {two.begin(), two.end()},
                    .cuts = {}};
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
        /// The triangles outside the patch on its boundary's cut edges, and their children.
        std::vector<std::uint32_t> outside;
        std::vector<TriangleIndices> outside_children;
    };
    // The triangle with the directed edge from a to b.
    auto with_edge = [&](std::uint32_t a, std::uint32_t b) {
        for (std::uint32_t j = first[a]; j < first[a + 1]; ++j) {
            const TriangleIndices& v = s.triangles[around[j]];
            for (int k = 0; k < 3; ++k)
                if (v[k] == a && v[(k + 1) % 3] == b) return around[j];
        }
        return none;
    };
    std::vector<Patch> patches;
    // Whether the corner and the cuts of a patch re-triangulated lie on the zero set (a crease
    // of two planes that do not meet on it is no crease).
    auto on_zero_set = [&](const Remeshed& made) {
        std::vector<Vec3> points;
        if (made.corner) points.push_back(*made.corner);
        for (const BoundaryCut& c : made.cuts) points.push_back(c.point);
        std::vector<double> values(points.size());
        g(points, values);
        return std::all_of(values.begin(), values.end(),
                           [&](double v) { return std::abs(v) <= eta; });
    };
    for (const std::uint32_t t0 : beyond) {
        if (taken[t0] || !bad[t0]) continue;
        ++stamps;
        // The triangles across a crease connected to t0 through their corners, a layer at a
        // time (their corners' planes asked first), up to max_fold triangles on at most
        // max_planes planes (more: a curved surface's facets, not a crease or corner).
        PlaneSet seen;
        auto few_planes = [&](std::uint32_t t) {
            for (const std::uint32_t v : s.triangles[t]) {
                seen.add_corner(planes, v);
                if (seen.size > max_planes) return false;
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
        // Once three or more of the planes met meet at a point of the zero set, the patch is
        // about that corner instead: grown no further along the creases that leave it.
        std::optional<Vec3> q;
        int tried = 0;  // the planes met when a corner was last looked for
        auto find_corner = [&] {
            if (!few || seen.size < 3 || seen.size == tried) return;
            tried = seen.size;
            q = meeting_point(seen.list(), s.vertices[s.triangles[t0][0]]);
            if (!q) return;
            double value = nan;
            g(std::span<const Vec3>(&*q, 1), std::span<double>(&value, 1));
            if (!(std::abs(value) <= eta)) q.reset();
        };
        find_corner();
        for (std::size_t done = 0; few && !q && done < patch.size() && patch.size() <= max_fold;) {
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
            find_corner();
        }
        if (!q && (!few || patch.size() > max_fold)) {
            for (const std::uint32_t t : patch) taken[t] = 1;
            continue;
        }
        // About a corner: the triangles within a distance of it connected to the patch, from
        // the patch's farthest corner out.
        double radius = 0.0;
        if (q) {
            for (const std::uint32_t t : patch)
                for (const std::uint32_t v : s.triangles[t])
                    radius = std::max(radius, distance(s.vertices[v], *q));
        }
        auto ball = [&] {
            ++stamps;
            for (const std::uint32_t t : patch) stamp[t] = stamps;
            for (std::size_t i = 0; i < patch.size(); ++i) {
                for (const std::uint32_t v : s.triangles[patch[i]]) {
                    for (std::uint32_t j = first[v]; j < first[v + 1]; ++j) {
                        const std::uint32_t t = around[j];
                        if (stamp[t] == stamps || taken[t]) continue;
                        stamp[t] = stamps;
                        if (closest_point(s.triangle(t), *q).distance2 <= radius * radius)
                            patch.push_back(t);
                    }
                }
            }
        };
        std::optional<Remeshed> made;
        for (int rings = 0; rings < max_rings && !made; ++rings) {
            if (q) {
                radius *= rings == 0 ? 1.0 : 1.5;
                ball();
                if (patch.size() > max_corner_patch) break;
            } else {
                const std::vector<std::uint32_t> more = ring(0, patch.size());
                patch.insert(patch.end(), more.begin(), more.end());
            }
            measure(std::span<const std::uint32_t>(patch));
            made = across_creases(s, planes, patch);
            if (made && !on_zero_set(*made)) made.reset();
        }
        for (const std::uint32_t t : patch) taken[t] = 1;
        // The triangles beyond its cut edges are split too: none may be another patch's.
        std::vector<std::uint32_t> outside;
        if (made) {
            for (const BoundaryCut& c : made->cuts) {
                const std::uint32_t t = with_edge(c.to, c.from);
                if (t == none || taken[t]) {
                    made.reset();
                    break;
                }
                if (std::find(outside.begin(), outside.end(), t) == outside.end())
                    outside.push_back(t);
            }
        }
        if (made)
            for (const std::uint32_t t : outside) taken[t] = 1;
        if (made) {
            patches.push_back({.removed = patch,
                               .made = std::move(*made),
                               .outside = std::move(outside),
                               .outside_children = {}});
        }
    }
    // The corners and cuts of boundaries: new vertices on all their planes.
    std::vector<std::uint8_t> keep(patches.size(), 1);
    {
        for (std::uint32_t i = 0; i < patches.size(); ++i) {
            Patch& p = patches[i];
            if (!p.made.corner && p.made.cuts.empty()) continue;
            std::vector<std::uint32_t> cut_at(p.made.cuts.size());
            if (p.made.corner) {
                p.corner = static_cast<std::uint32_t>(s.vertices.size());
                s.vertices.push_back(*p.made.corner);
            }
            for (std::size_t k = 0; k < p.made.cuts.size(); ++k) {
                cut_at[k] = static_cast<std::uint32_t>(s.vertices.size());
                s.vertices.push_back(p.made.cuts[k].point);
            }
            planes.resize(s.vertices.size());
            if (p.made.corner) {
                planes.set(p.corner, p.made.planes);
                planes.measured[p.corner] = 1;
            }
            for (std::size_t k = 0; k < p.made.cuts.size(); ++k) {
                const std::array<CreasePlane, 2> both{p.made.cuts[k].a, p.made.cuts[k].b};
                planes.set(cut_at[k], both);
                planes.measured[cut_at[k]] = 1;
            }
            for (TriangleIndices& t : p.made.triangles) {
                for (std::uint32_t& v : t) {
                    if (v == corner_vertex)
                        v = p.corner;
                    else if (v > corner_vertex - 1 - p.made.cuts.size())
                        v = cut_at[corner_vertex - 1 - v];
                }
            }
            // Each triangle outside, split on its edges cut.
            for (const std::uint32_t t : p.outside) {
                const TriangleIndices& v = s.triangles[t];
                unsigned mask = 0;
                std::array<std::uint32_t, 3> w{none, none, none};
                for (std::size_t k = 0; k < p.made.cuts.size(); ++k) {
                    const BoundaryCut& c = p.made.cuts[k];
                    for (int e = 0; e < 3; ++e)
                        if (v[e] == c.to && v[(e + 1) % 3] == c.from)
                            mask |= 1u << e, w[e] = cut_at[k];
                }
                split_children(s, v, mask, w, p.outside_children);
            }
        }
    }
    // The surface with every patch replaced; a patch whose triangles meet the rest is put back.
    for (;;) {
        Surface next;
        next.vertices = s.vertices;
        std::vector<std::uint8_t> removed(n, 0);
        for (std::size_t i = 0; i < patches.size(); ++i)
            if (keep[i]) {
                for (const std::uint32_t t : patches[i].removed) removed[t] = 1;
                for (const std::uint32_t t : patches[i].outside) removed[t] = 1;
            }
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
            for (const auto* list : {&patches[i].made.triangles, &patches[i].outside_children}) {
                for (const TriangleIndices& t : *list) {
                    next.triangles.push_back(t);
                    next_centroid.push_back(nan);
                    next_dirty.push_back(1);
                    owner.push_back(i);
                }
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

bool folds_beyond(const Surface& s, const CreasePlanes& planes, const TriangleIndices& t0,
                  const TriangleIndices& t1, const TriangleIndices& u, const TriangleIndices& v,
                  double eps) {
    auto known = [&](const TriangleIndices& t) {
        return t[0] < planes.count.size() && t[1] < planes.count.size() &&
               t[2] < planes.count.size();
    };
    if (!known(t0) || !known(t1) || !common_plane(planes, t0) || !common_plane(planes, t1))
        return false;
    // The distance of x from the nearest plane of the corners of t.
    auto off = [&](const TriangleIndices& t, Vec3 x) {
        double least = std::numeric_limits<double>::infinity();
        for (const std::uint32_t w : t)
            for (const CreasePlane& p : planes.of(w))
                least = std::min(least, std::abs(dot(p.n, x) - p.c));
        return least;
    };
    for (const TriangleIndices* t : {&u, &v}) {
        if (common_plane(planes, *t)) continue;
        const Vec3 a = s.vertices[(*t)[0]], b = s.vertices[(*t)[1]], c = s.vertices[(*t)[2]];
        for (const Vec3 point : {(a + b + c) / 3.0, 0.5 * (a + c)})
            if (off(*t, point) > eps) return true;
    }
    return false;
}

std::size_t cut_creases(Surface& s, const SpaceEvaluator& g, double eta,
                        std::span<const std::uint32_t> beyond, CreasePlanes& planes,
                        std::vector<double>& centroid_value, std::vector<std::uint8_t>& dirty) {
    const std::size_t old_vertices = s.vertices.size();
    planes.resize(old_vertices);

    std::vector<std::pair<std::uint32_t, Vec3>> moved_from;  // vertices moved, where they were
    std::size_t moves = 0;                                   // of them checked
    // The moves not yet checked: one off the zero set (planes measured beside it that meet
    // elsewhere than its facets do), or whose triangles meet the rest of the surface, is undone.
    auto check_moves = [&] {
        bool evaluated = false;
        for (std::size_t first_move = moves; moved_from.size() > first_move;) {
            std::vector<std::uint8_t> moved(s.vertices.size(), 0), around_moved(s.size(), 0);
            for (std::size_t k = first_move; k < moved_from.size(); ++k)
                moved[moved_from[k].first] = 1;
            for (std::uint32_t t = 0; t < s.size(); ++t) {
                const TriangleIndices& v = s.triangles[t];
                around_moved[t] = moved[v[0]] || moved[v[1]] || moved[v[2]];
            }
            std::vector<std::uint8_t> undo(s.vertices.size(), 0);
            bool any = false;
            if (!evaluated) {
                evaluated = true;
                std::vector<Vec3> at;
                for (std::size_t k = first_move; k < moved_from.size(); ++k)
                    at.push_back(s.vertices[moved_from[k].first]);
                std::vector<double> values(at.size());
                g(at, values);
                for (std::size_t k = first_move; k < moved_from.size(); ++k) {
                    if (std::abs(values[k - first_move]) <= eta) continue;
                    undo[moved_from[k].first] = 1;
                    any = true;
                }
            }
            // A triangle left (nearly) without area, or meeting the rest of the surface.
            if (!any) {
                for (std::uint32_t t = 0; t < s.size(); ++t) {
                    if (!around_moved[t]) continue;
                    const Triangle3 x = s.triangle(t);
                    if (has_area(x.a, x.b, x.c)) continue;
                    for (const std::uint32_t v : s.triangles[t]) undo[v] = moved[v];
                    any = true;
                }
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
            const CreasePlane plane{unit, dot(unit, s.vertices[u]) - at / norm(n)};
            planes.set(u, {&plane, 1});
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
                    for (const CreasePlane& p : planes.of(u))
                        if (std::abs(dot(p.n, x) - p.c) <= tolerance) near[i].add(p);
                }
            }
        }
        // Such a corner is moved onto its planes (their crease, or where three meet), where the
        // zero set is; the caller forgets what it knew of G about it.
        for (std::size_t i = 0; i < todo.size(); ++i) {
            const int count = near[i].size;
            if (count == 0 || count > max_planes) continue;
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
            planes.set(u, near[i].list());
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
                const CreasePlane a = planes.of(u)[0], b = planes.of(w)[0];
                if (same_plane(a, b)) continue;
                const std::optional<Crossing> c = crossing(s.vertices[u], s.vertices[w], a, b);
                if (!c || (c->s >= snap_fraction && c->s <= 1.0 - snap_fraction)) continue;
                const std::uint32_t end = c->s < snap_fraction ? u : w;
                const Vec3 to = onto_crease(s.vertices[end], a, b);
                moved_from.emplace_back(end, s.vertices[end]);
                s.vertices[end] = to;
                planes.moved.push_back(end);
                const std::array<CreasePlane, 2> both{a, b};
                planes.set(end, both);
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
                const CreasePlane a = planes.of(u)[0], b = planes.of(w)[0];
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
        const std::array<CreasePlane, 2> both{c.a, c.b};
        planes.set(c.vertex, both);
        planes.measured[c.vertex] = 1;
    }
    for (const Centre& c : centres) {
        if (!c.alive) continue;
        planes.set(c.vertex, c.planes);
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
