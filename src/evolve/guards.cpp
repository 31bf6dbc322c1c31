// The run loop's physical guards: a step's curves against what the law's exact motion keeps.
#include "slc/evolve/guards.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace slc {

RegionParts region_parts(const Interface& curves) {
    RegionParts r;
    for (std::size_t c = 0; c < curves.curve_count(); ++c)
        ++(signed_area(curves.curve(c)) >= 0.0 ? r.parts : r.holes);
    return r;
}

namespace {

/// Counterclockwise curves (positive area) minus clockwise ones (holes).
int signed_curve_count(const Interface& curves) {
    const RegionParts p = region_parts(curves);
    return static_cast<int>(p.parts) - static_cast<int>(p.holes);
}

}  // namespace

RegionParts region_parts(const Surface& surface) {
    const auto label = component_labels(surface);
    std::vector<double> six_volume;
    for (std::size_t t = 0; t < surface.size(); ++t) {
        if (label[t] >= six_volume.size()) six_volume.resize(label[t] + 1, 0.0);
        const auto& [a, b, c] = surface.triangles[t];
        six_volume[label[t]] +=
            dot(surface.vertices[a], cross(surface.vertices[b], surface.vertices[c]));
    }
    RegionParts r;
    for (double v : six_volume) ++(v >= 0.0 ? r.parts : r.holes);
    return r;
}

ShapeTopology shape_topology(const Interface& curves) {
    return {curves.curve_count(), static_cast<long long>(region_parts(curves).holes)};
}

ShapeTopology shape_topology(const Surface& surface) {
    return {component_count(surface), genus(surface)};
}

std::string describe(const ShapeTopology& t, int dim) {
    return fmt::format(
        "{} {} with {} {}", t.components, t.components == 1 ? "component" : "components", t.holes,
        dim == 2 ? (t.holes == 1 ? "hole" : "holes") : (t.holes == 1 ? "handle" : "handles"));
}

std::optional<std::string> lost_topology_note(const ShapeTopology& given,
                                              const ShapeTopology& contour, int dim,
                                              const std::string& advice) {
    if (given == contour) return std::nullopt;
    return fmt::format(
        "the contour has {} where the input has {}: a part is thinner than its cells resolve; {} "
        "(a part that tapers to an edge of no thickness is thinner at every depth)",
        describe(contour, dim), describe(given, dim), advice);
}

std::optional<std::string> region_parts_violation(const Invariants& law, RegionParts before,
                                                  RegionParts after) {
    if (law.cannot_vanish && after.parts > before.parts) {
        return fmt::format(
            "the region's parts rose from {} to {} under a law that only grows it (growing parts "
            "merge, never split)",
            before.parts, after.parts);
    }
    if (law.cannot_grow && after.holes > before.holes) {
        return fmt::format(
            "the region's holes rose from {} to {} under a law that only shrinks it (its holes "
            "merge, never split or appear)",
            before.holes, after.holes);
    }
    return std::nullopt;
}

std::optional<double> growth_above_least(RunLeast& least, double x, double t, double fraction,
                                         double slack) {
    if (least.value == 0.0 || x < least.value) {
        least = {x, t};
        return std::nullopt;
    }
    if (x > least.value * (1.0 + fraction) + slack) return (x - least.value) / least.value;
    return std::nullopt;
}

std::optional<double> area_change_expected(const Invariants& law, const Interface& before,
                                           double area_before, const Interface& after, double k,
                                           const GuardBudget& budget) {
    if (law.area_rate && !before.empty()) return *law.area_rate * k;
    // Curves smaller than a cell are not resolved: their area moves as the tree allows.
    if (!law.area_rate_per_curve || before.empty() || after.curve_count() != before.curve_count() ||
        !(std::abs(area_before) > budget.resolved_area))
        return std::nullopt;
    return *law.area_rate_per_curve * signed_curve_count(before) * k;
}

std::optional<std::string> invariant_violation(const Invariants& law, const Interface& before,
                                               const CurveMeasures& m0, const Interface& after,
                                               const CurveMeasures& m1, double k, double eps,
                                               const GuardBudget& budget) {
    if (before.empty()) return std::nullopt;
    const double a0 = m0.area, a1 = m1.area, l0 = m0.length, l1 = m1.length;
    const double eps_tolerance = budget.eps_lengths * eps * l0;
    const double tolerance =
        std::max(budget.area_fraction * std::max(std::abs(a0), std::abs(a1)), eps_tolerance);
    if (after.empty()) {
        if (law.keeps_area) return "the curves vanished under a law that keeps their area";
        if (law.cannot_vanish) return "the curves vanished under a law that only grows them";
        if (law.area_rate_per_curve) {
            const double rate = *law.area_rate_per_curve * signed_curve_count(before);
            // The curves vanish within the step only if the law takes their area within it,
            // up to what the tree does not resolve: the first-order step vanishes them later
            // than the exact flow, not earlier.
            if (rate < 0.0 &&
                std::abs(a0) > std::abs(rate) * k + std::max(eps_tolerance, budget.resolved_area)) {
                return fmt::format(
                    "the curves vanished with area {:.3g} left, which the law takes {:.3g} to "
                    "lose",
                    a0, std::abs(a0 / rate));
            }
        }
        return std::nullopt;
    }
    if (law.cannot_split && after.curve_count() > before.curve_count()) {
        return fmt::format(
            "the number of curves rose from {} to {} under a law that cannot split "
            "them",
            before.curve_count(), after.curve_count());
    }
    if (auto v = shape_parts_violation(law, before, after)) return v;
    if (law.rigid && after.curve_count() != before.curve_count()) {
        return fmt::format("a rigid motion changed the number of curves from {} to {}",
                           before.curve_count(), after.curve_count());
    }
    if (law.shortens) {
        if (l1 > l0 * (1.0 + budget.length_fraction) + eps_tolerance) {
            return fmt::format(
                "the length grew by {:.3g}% in one step under a law that shortens the curves",
                100.0 * (l1 - l0) / l0);
        }
    }
    if (law.cannot_vanish && a1 < a0 - tolerance) {
        return fmt::format("the area fell by {:.3g}% in one step under a law that only grows it",
                           100.0 * (a0 - a1) / std::abs(a0));
    }
    if (law.rigid) {
        // A step of length k of a run of length T gets rigid_run_fraction·k/T of the length, at
        // most a step's own fraction; the area may drift by rigid_run_fraction over the run.
        const double share = budget.run_length > 0.0
                                 ? budget.rigid_run_fraction * k / budget.run_length
                                 : std::numeric_limits<double>::infinity();
        const auto allowed = [&](double fraction) {
            return share < fraction ? fmt::format("its share {:.3g}% of the run's {:g}%",
                                                  100.0 * share, 100.0 * budget.rigid_run_fraction)
                                    : fmt::format("{:g}%", 100.0 * fraction);
        };
        if (std::abs(a1 - a0) >
            std::max(budget.area_fraction * std::max(std::abs(a0), std::abs(a1)), eps_tolerance)) {
            return fmt::format(
                "the area changed by {:.3g}% in one step of a rigid motion, more than {:g}%",
                100.0 * (a1 - a0) / std::abs(a0), 100.0 * budget.area_fraction);
        }
        const double a_start = budget.start_area;
        if (a_start != 0.0 &&
            std::abs(a1 - a_start) >
                std::max(budget.rigid_run_fraction * std::abs(a_start), eps_tolerance)) {
            return fmt::format(
                "the area has drifted by {:.3g}% since the start of the run under a rigid "
                "motion, more than the run's {:g}%",
                100.0 * (a1 - a_start) / std::abs(a_start), 100.0 * budget.rigid_run_fraction);
        }
        // The length is kept too, and a contour whose vertices lie on the moved curve cannot
        // be longer than it (its chords cut the corners, so it may be shorter): noise that
        // roughens the curves shows there before it shows in the area.
        const double length_share = std::min(share, budget.length_fraction);
        if (l1 > l0 * (1.0 + length_share) + budget.eps_lengths * eps) {
            return fmt::format(
                "the length grew by {:.3g}% in one step of a rigid motion, more than {}",
                100.0 * (l1 - l0) / l0, allowed(budget.length_fraction));
        }
    }
    if (law.keeps_area && std::abs(a1 - a0) > tolerance) {
        return fmt::format("the area changed by {:.3g}% in one step under a law that keeps it",
                           100.0 * (a1 - a0) / std::abs(a0));
    }
    if (const auto expected = area_change_expected(law, before, a0, after, k, budget)) {
        if (std::abs((a1 - a0) - *expected) >
            std::max(budget.rate_fraction * std::abs(*expected), eps_tolerance)) {
            return fmt::format(
                "the area changed by {:.3g} in one step where the law changes it "
                "by {:.3g}",
                a1 - a0, *expected);
        }
    }
    return std::nullopt;
}

}  // namespace slc
