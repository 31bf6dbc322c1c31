// Interface storage and its measures: area (shoelace) and length; the regions its curves bound.
#include "slc/geometry/interface.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "slc/core/error.hpp"
#include "slc/geometry/predicates.hpp"

namespace slc {

Interface::Interface(const std::vector<std::vector<Vec2>>& curves) {
    for (std::size_t c = 0; c < curves.size(); ++c) {
        if (curves[c].size() < 3) {
            throw InvalidInput(fmt::format(
                "curve {} has {} points; a closed curve needs at least 3", c, curves[c].size()));
        }
        points_.insert(points_.end(), curves[c].begin(), curves[c].end());
        curve_index_.insert(curve_index_.end(), curves[c].size(), c);
        offsets_.push_back(points_.size());
    }
}

void Interface::reverse_curve(std::size_t c) {
    std::reverse(points_.begin() + static_cast<std::ptrdiff_t>(offsets_[c]),
                 points_.begin() + static_cast<std::ptrdiff_t>(offsets_[c + 1]));
}

std::vector<std::vector<Vec2>> Interface::curves() const {
    std::vector<std::vector<Vec2>> out;
    out.reserve(curve_count());
    for (std::size_t c = 0; c < curve_count(); ++c) {
        auto pts = curve(c);
        out.emplace_back(pts.begin(), pts.end());
    }
    return out;
}

std::vector<Vec2> vertices_and_midpoints(const Interface& curves) {
    std::vector<Vec2> points;
    points.reserve(2 * curves.size());
    points.assign(curves.points().begin(), curves.points().end());
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        points.push_back(0.5 * (s.a + s.b));
    }
    return points;
}

double signed_area(std::span<const Vec2> curve) {
    // Shoelace formula about the first vertex, which keeps the terms small for curves far from
    // the origin.
    double twice = 0.0;
    const Vec2 o = curve.empty() ? Vec2{} : curve[0];
    for (std::size_t i = 1; i + 1 < curve.size(); ++i)
        twice += cross(curve[i] - o, curve[i + 1] - o);
    return 0.5 * twice;
}

double area(const Interface& curves) {
    double total = 0.0;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) total += signed_area(curves.curve(c));
    return total;
}

double length(std::span<const Vec2> curve) {
    double total = 0.0;
    for (std::size_t i = 0; i < curve.size(); ++i)
        total += distance(curve[i], curve[(i + 1) % curve.size()]);
    return total;
}

double length(const Interface& curves) {
    double total = 0.0;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        total += distance(s.a, s.b);
    }
    return total;
}

bool encloses(const Interface& curves, std::size_t c, Vec2 p) {
    // Half-open in y, so a vertex on the ray counts once.
    bool inside = false;
    for (std::size_t i = curves.offsets()[c]; i < curves.offsets()[c + 1]; ++i) {
        const Segment s = curves.segment(i);
        if ((s.a.y > p.y) != (s.b.y > p.y)) {
            // p lies left of an upward segment (right of a downward one) iff the segment meets
            // the ray right of p.
            const int side = orientation(s.a, s.b, p);
            if (s.b.y > s.a.y ? side > 0 : side < 0) inside = !inside;
        }
    }
    return inside;
}

std::vector<std::size_t> curve_regions(const Interface& curves) {
    const std::size_t count = curves.curve_count();
    std::vector<double> areas(count);
    std::vector<std::size_t> region(count, 0);
    std::size_t regions = 0;
    for (std::size_t c = 0; c < count; ++c) {
        areas[c] = signed_area(curves.curve(c));
        if (areas[c] > 0) region[c] = regions++;
    }
    for (std::size_t c = 0; c < count; ++c) {
        if (areas[c] > 0) continue;
        std::optional<std::size_t> best;
        for (std::size_t o = 0; o < count; ++o)
            if (areas[o] > 0 && encloses(curves, o, curves.curve(c)[0]) &&
                (!best || areas[o] < areas[*best]))
                best = o;
        if (!best)
            throw InvalidInput(fmt::format("curve {} is a hole (clockwise) inside no curve", c));
        region[c] = region[*best];
    }
    return region;
}

std::optional<std::size_t> region_containing(const Interface& curves,
                                             std::span<const std::size_t> region, Vec2 x) {
    std::optional<std::size_t> best;
    double best_area = 0.0;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const double a = signed_area(curves.curve(c));
        if (a > 0 && encloses(curves, c, x) && (!best || a < best_area)) {
            best = region[c];
            best_area = a;
        }
    }
    if (!best) return std::nullopt;
    for (std::size_t c = 0; c < curves.curve_count(); ++c)
        if (region[c] == *best && signed_area(curves.curve(c)) < 0 && encloses(curves, c, x))
            return std::nullopt;  // in a hole of that region
    return best;
}

}  // namespace slc
