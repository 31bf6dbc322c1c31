// Interface storage and its measures: area (shoelace) and length.
#include "slc/geometry/interface.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "slc/core/error.hpp"

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

}  // namespace slc
