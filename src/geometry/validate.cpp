// Validation of user-given curves (DESIGN §2): the Shamos–Hoey sweep that finds a crossing in
// O(N log N) (M. I. Shamos and D. Hoey, "Geometric intersection problems", FOCS 1976), with the
// degenerate cases handled as in de Berg et al., "Computational Geometry", §2.1, and
// prepare_interface, which checks raw curves in the order its header lists and orients them by
// nesting depth.
#include "slc/geometry/validate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <span>
#include <utility>

#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/geometry/predicates.hpp"

namespace slc {

namespace {

// ---------------------------------------------------------------------------------------------
// The sweep. Points are ordered lexicographically by (x, y): the sweep line is vertical, and along
// it the points below the current event have already been swept (as if the line were tilted
// infinitesimally), so vertical segments and events sharing an x coordinate need no special case.

bool lex_less(Vec2 p, Vec2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); }

/// Consecutive segments p→q and q→r meet at more than q: they are collinear and r lies on the
/// same side of q as p, so the curve folds back over itself. Exact.
bool folds_back(Vec2 p, Vec2 q, Vec2 r) {
    return p != q && r != q && orientation(p, q, r) == 0 && lex_less(p, q) == lex_less(r, q);
}

/// True if segments i and j intersect other than consecutive segments meeting at their vertex.
bool is_forbidden(const Interface& curves, std::size_t i, std::size_t j) {
    if (i == j || !segments_intersect(curves.segment(i), curves.segment(j))) return false;
    if (curves.next(i) == j) {
        return folds_back(curves.point(i), curves.point(j), curves.point(curves.next(j)));
    }
    if (curves.next(j) == i) {
        return folds_back(curves.point(j), curves.point(i), curves.point(curves.next(i)));
    }
    return true;
}

Crossing ordered(std::size_t i, std::size_t j) { return {std::min(i, j), std::max(i, j)}; }

/// A segment with its endpoints in sweep order.
struct SweepSegment {
    Vec2 left;
    Vec2 right;
};

/// The order of the status structure: by height where the sweep line meets the segments. Two
/// segments are compared at the later of their left endpoints, where both are on the line; two
/// starting at one point are compared by direction; exact ties (possible only after a crossing,
/// which ends the sweep) fall back to the index. A point q compares with a segment by its side.
class StatusOrder {
public:
    using is_transparent = void;
    explicit StatusOrder(const std::vector<SweepSegment>& segments) : segments_(&segments) {}

    bool operator()(std::size_t a, std::size_t b) const {
        if (a == b) return false;
        const SweepSegment& s = (*segments_)[a];
        const SweepSegment& t = (*segments_)[b];
        int o = 0;
        if (s.left == t.left) {
            o = orientation(s.left, s.right, t.right);  // > 0: t turns left of s, so s is below
        } else if (lex_less(t.left, s.left)) {
            o = -orientation(t.left, t.right, s.left);  // > 0: s starts right of t, below it
        } else {
            o = orientation(s.left, s.right, t.left);  // > 0: t starts left of s, above it
        }
        return o != 0 ? o > 0 : a < b;
    }
    /// Segment a passes strictly below point q.
    bool operator()(std::size_t a, Vec2 q) const { return side(a, q) > 0; }
    /// Segment a passes strictly above point q.
    bool operator()(Vec2 q, std::size_t a) const { return side(a, q) < 0; }

private:
    int side(std::size_t a, Vec2 q) const {
        return orientation((*segments_)[a].left, (*segments_)[a].right, q);
    }
    const std::vector<SweepSegment>* segments_;
};

/// An endpoint of a segment; a segment of zero length has a single event.
struct Event {
    Vec2 point;
    std::size_t segment = 0;
};

class Sweep {
public:
    explicit Sweep(const Interface& curves) : curves_(curves), status_(StatusOrder(segments_)) {
        segments_.reserve(curves.size());
        events_.reserve(2 * curves.size());
        for (std::size_t i = 0; i < curves.size(); ++i) {
            const Segment s = curves.segment(i);
            const bool forward = lex_less(s.a, s.b) || s.a == s.b;
            segments_.push_back(forward ? SweepSegment{s.a, s.b} : SweepSegment{s.b, s.a});
            events_.push_back({segments_[i].left, i});
            if (s.a != s.b) events_.push_back({segments_[i].right, i});
        }
        std::sort(events_.begin(), events_.end(), [](const Event& e, const Event& f) {
            if (e.point != f.point) return lex_less(e.point, f.point);
            return e.segment < f.segment;
        });
    }

    std::optional<Crossing> run() {
        for (std::size_t begin = 0; begin < events_.size();) {
            std::size_t end = begin + 1;
            while (end < events_.size() && events_[end].point == events_[begin].point) ++end;
            if (auto crossing = process(begin, end)) return crossing;
            begin = end;
        }
        return std::nullopt;
    }

private:
    using Status = std::set<std::size_t, StatusOrder>;

    /// All events at one point q: events_[begin, end).
    std::optional<Crossing> process(std::size_t begin, std::size_t end) {
        const Vec2 q = events_[begin].point;
        if (auto c = crossing_among_events(begin, end)) return c;

        // Segments of the status through q: those ending at q, and any with q in its interior.
        auto [first, last] = status_.equal_range(q);
        for (auto it = first; it != last; ++it) {
            if (segments_[*it].right != q) return report(*it, events_[begin].segment);
        }
        SLC_ASSERT(
            static_cast<std::size_t>(std::distance(first, last)) == count_ending(begin, end, q),
            "the segments ending at an event are found in the status");
        auto above = status_.erase(first, last);
        const bool has_below = above != status_.begin();
        const auto below = has_below ? std::prev(above) : status_.end();

        bool inserted = false;
        for (std::size_t e = begin; e < end; ++e) {
            const SweepSegment& s = segments_[events_[e].segment];
            if (s.left == q && s.right != q) {
                status_.insert(events_[e].segment);
                inserted = true;
            }
        }
        // Check the pairs that have just become neighbours.
        if (!inserted) {
            if (has_below && above != status_.end()) return check(*below, *above);
            return std::nullopt;
        }
        const auto lowest = has_below ? std::next(below) : status_.begin();
        if (has_below) {
            if (auto c = check(*below, *lowest)) return c;
        }
        if (above != status_.end()) return check(*std::prev(above), *above);
        return std::nullopt;
    }

    /// Segments with an endpoint at the same point q meet there; any two that are not consecutive
    /// segments joined at q are a crossing. Among any three such segments there is a crossing
    /// pair (three pairwise consecutive segments make a whole curve of three vertices, which then
    /// folds back), so the loop ends within its first three segments: O(1) per event.
    std::optional<Crossing> crossing_among_events(std::size_t begin, std::size_t end) const {
        for (std::size_t j = begin + 1; j < end; ++j) {
            for (std::size_t i = begin; i < j; ++i) {
                if (auto c = check(events_[i].segment, events_[j].segment)) return c;
            }
        }
        return std::nullopt;
    }

    std::size_t count_ending(std::size_t begin, std::size_t end, Vec2 q) const {
        return static_cast<std::size_t>(std::count_if(
            events_.begin() + static_cast<std::ptrdiff_t>(begin),
            events_.begin() + static_cast<std::ptrdiff_t>(end), [&](const Event& e) {
                return segments_[e.segment].right == q && segments_[e.segment].left != q;
            }));
    }

    std::optional<Crossing> check(std::size_t i, std::size_t j) const {
        if (is_forbidden(curves_, i, j)) return ordered(i, j);
        return std::nullopt;
    }

    /// Segment t has the event point in its interior, so it meets segment e there.
    Crossing report(std::size_t t, std::size_t e) const {
        SLC_ASSERT(is_forbidden(curves_, t, e), "a point inside a segment is a crossing");
        return ordered(t, e);
    }

    const Interface& curves_;
    std::vector<SweepSegment> segments_;
    std::vector<Event> events_;
    Status status_;
};

// ---------------------------------------------------------------------------------------------
// prepare_interface, one step per item of the list in the header.

using RawCurves = std::vector<std::vector<Vec2>>;

void check_finite(const RawCurves& raw) {
    for (std::size_t c = 0; c < raw.size(); ++c) {
        for (std::size_t v = 0; v < raw[c].size(); ++v) {
            const Vec2 p = raw[c][v];
            if (!is_finite(p)) {
                throw InvalidInput(fmt::format("curve {}, vertex {}: coordinate is not finite ({})",
                                               c, v, std::isfinite(p.x) ? p.y : p.x));
            }
            if (std::max(std::abs(p.x), std::abs(p.y)) > tolerance::max_coordinate) {
                throw InvalidInput(fmt::format(
                    "curve {}, vertex {}: point ({}, {}) is beyond the coordinate limit ±{:g}", c,
                    v, p.x, p.y, tolerance::max_coordinate));
            }
        }
    }
}

void check_inside(const RawCurves& raw, const Box& domain) {
    for (std::size_t c = 0; c < raw.size(); ++c) {
        for (std::size_t v = 0; v < raw[c].size(); ++v) {
            const Vec2 p = raw[c][v];
            if (!domain.contains(p)) {
                throw InvalidInput(fmt::format(
                    "curve {}, vertex {}: point ({}, {}) lies outside the domain [{}, {}]x[{}, {}]",
                    c, v, p.x, p.y, domain.lo.x, domain.hi.x, domain.lo.y, domain.hi.y));
            }
        }
    }
}

/// The length below which two consecutive points are one: tolerance::duplicate_point times the
/// width of the domain, or of the bounding box of all points when no domain is given.
double duplicate_distance(const RawCurves& raw, const std::optional<Box>& domain) {
    Box box = domain.value_or(Box::empty());
    if (!domain) {
        for (const auto& curve : raw) box = unite(box, bounding_box(curve));
    }
    if (box.is_empty()) return 0.0;
    // Half-widths, so that a box spanning nearly all doubles does not overflow to infinity.
    const double half_width =
        std::max(0.5 * box.hi.x - 0.5 * box.lo.x, 0.5 * box.hi.y - 0.5 * box.lo.y);
    return 2.0 * tolerance::duplicate_point * half_width;
}

/// One curve without its consecutive duplicates, and the input index of each vertex kept.
struct CleanCurve {
    std::vector<Vec2> points;
    std::vector<std::size_t> input_index;
};

/// Drops every point within tol of the last point kept (the first of a run stays), then the
/// last points while they repeat the first.
CleanCurve without_duplicates(const std::vector<Vec2>& curve, double tol) {
    CleanCurve clean;
    for (std::size_t v = 0; v < curve.size(); ++v) {
        if (!clean.points.empty() && distance(clean.points.back(), curve[v]) <= tol) continue;
        clean.points.push_back(curve[v]);
        clean.input_index.push_back(v);
    }
    while (clean.points.size() > 1 && distance(clean.points.back(), clean.points.front()) <= tol) {
        clean.points.pop_back();
        clean.input_index.pop_back();
    }
    return clean;
}

void check_crossings(const Interface& curves, const std::vector<CleanCurve>& clean) {
    const std::optional<Crossing> crossing = find_crossing(curves);
    if (!crossing) return;
    const std::size_t c1 = curves.curve_of(crossing->first);
    const std::size_t c2 = curves.curve_of(crossing->second);
    // Segments are named by the input index of their first vertex.
    const std::size_t s1 = clean[c1].input_index[crossing->first - curves.offsets()[c1]];
    const std::size_t s2 = clean[c2].input_index[crossing->second - curves.offsets()[c2]];
    if (c1 == c2) {
        throw InvalidInput(
            fmt::format("curve {} crosses itself: segment {} meets segment {}", c1, s1, s2));
    }
    throw InvalidInput(
        fmt::format("curve {} crosses curve {} (segment {} of curve {} meets "
                    "segment {} of curve {})",
                    c1, c2, s1, c1, s2, c2));
}

/// How many other curves enclose curve c. The curves are disjoint, so one vertex decides.
std::size_t nesting_depth(const Interface& curves, const std::vector<Box>& boxes, std::size_t c) {
    const Vec2 p = curves.point(curves.offsets()[c]);
    std::size_t depth = 0;
    for (std::size_t d = 0; d < curves.curve_count(); ++d) {
        if (d != c && boxes[d].contains(p) && encloses(curves, d, p)) ++depth;
    }
    return depth;
}

/// +1 if the simple curve c is counterclockwise, −1 if clockwise: the turn at its
/// lexicographically lowest vertex, which is convex. Exact.
int curve_orientation(const Interface& curves, std::size_t c) {
    std::size_t v = curves.offsets()[c];
    for (std::size_t i = v + 1; i < curves.offsets()[c + 1]; ++i) {
        if (lex_less(curves.point(i), curves.point(v))) v = i;
    }
    const int turn =
        orientation(curves.point(curves.prev(v)), curves.point(v), curves.point(curves.next(v)));
    SLC_ASSERT(turn != 0, "the lowest vertex of a simple curve is a strict turn");
    return turn;
}

/// Reverses every curve whose orientation disagrees with its nesting depth, noting each.
std::vector<std::string> orient_by_nesting(Interface& curves) {
    std::vector<Box> boxes;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        boxes.push_back(bounding_box(curves.curve(c)));
    }
    std::vector<std::size_t> depth;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        depth.push_back(nesting_depth(curves, boxes, c));
    }
    std::vector<std::string> notes;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const bool is_hole = depth[c] % 2 == 1;
        const bool is_counterclockwise = curve_orientation(curves, c) > 0;
        if (is_hole == is_counterclockwise) {
            curves.reverse_curve(c);
            notes.push_back(
                fmt::format("curve {} {}", c,
                            is_hole ? "is a hole and was counterclockwise; reoriented clockwise"
                                    : "was clockwise; reoriented counterclockwise"));
        }
    }
    return notes;
}

}  // namespace

std::optional<Crossing> find_crossing(const Interface& curves) { return Sweep(curves).run(); }

// Vertices and segments in messages are numbered from 0 as in the input; segment k starts at
// input vertex k.
PreparedInterface prepare_interface(const std::vector<std::vector<Vec2>>& raw,
                                    const std::optional<Box>& domain) {
    if (raw.empty()) throw InvalidInput("no curves: the interface is empty");
    check_finite(raw);
    if (domain) check_inside(raw, *domain);

    const double tol = duplicate_distance(raw, domain);
    std::vector<CleanCurve> clean;
    RawCurves points;
    for (std::size_t c = 0; c < raw.size(); ++c) {
        clean.push_back(without_duplicates(raw[c], tol));
        if (clean[c].points.size() < 3) {
            // Points that differ but lie within tol of each other: say so, with the tolerance.
            const std::set<std::pair<double, double>> exact = [&] {
                std::set<std::pair<double, double>> out;
                for (const Vec2 p : raw[c]) out.emplace(p.x, p.y);
                return out;
            }();
            const std::string why =
                exact.size() > clean[c].points.size()
                    ? fmt::format(" (points closer than {:.3g} are one at this scale)", tol)
                    : "";
            throw InvalidInput(
                fmt::format("curve {} has {} distinct points{}; a closed curve needs at least 3", c,
                            clean[c].points.size(), why));
        }
        points.push_back(clean[c].points);
    }

    PreparedInterface prepared{Interface(points), {}};
    check_crossings(prepared.curves, clean);
    prepared.notes = orient_by_nesting(prepared.curves);
    return prepared;
}

}  // namespace slc
