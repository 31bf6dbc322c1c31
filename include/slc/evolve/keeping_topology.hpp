/// @file
/// The thin depth that keeps a user's shape (written once for curves and surfaces, for slc
/// contour and the Python package): where the contour at the thin depth asked for loses the
/// shape's components or holes, the other thin depths in the order a run's start tries them.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "slc/core/error.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/evolve/overrides.hpp"

namespace slc {

/// A contour of a user's shape at the thin depth that keeps the shape's components and holes,
/// where one does: `at(thin)` contours at that thin depth, `topology_of` tells a contour's. For a
/// thin depth left at its default: at the one `asked` first; when that loses the shape's
/// topology, the shallower ones, deepest first, then deeper ones two levels at a time up to the
/// most while they change the topology, as a run's start tries them (thin
/// cells following a sharp edge or point catch it unevenly; a wall thinner than the cells wants
/// deeper ones; one that fails, as where G vanishes along a knife edge, keeps none). Returns the
/// thin depth kept and its contour: the first's when none keeps the shape.
template <class At, class TopologyOf>
auto keeping_topology(const ShapeTopology& given, int asked, At at, TopologyOf topology_of) {
    using Contour = decltype(at(asked));
    Contour first = at(asked);
    ShapeTopology before = topology_of(first);
    if (before == given) return std::pair{asked, std::move(first)};
    auto attempt = [&](int thin) -> std::optional<Contour> {
        try {
            return at(thin);
        } catch (const NumericalFailure&) {
            return std::nullopt;
        }
    };
    for (int shallower = asked - 1; shallower >= 0; --shallower) {
        std::optional<Contour> other = attempt(shallower);
        if (other && topology_of(*other) == given) return std::pair{shallower, std::move(*other)};
    }
    for (int deeper = asked + 2; asked > 0 && deeper <= setting_range::thin_depth.hi; deeper += 2) {
        std::optional<Contour> other = attempt(deeper);
        if (!other) break;
        const ShapeTopology got = topology_of(*other);
        if (got == given) return std::pair{deeper, std::move(*other)};
        if (got == before) break;  // deeper cells change nothing: thinner than any
        before = got;
    }
    return std::pair{asked, std::move(first)};
}

/// The note when keeping_topology kept another thin depth than the one asked for, naming the
/// setting as the caller does (`--thin-depth`, `thin_depth`); nothing when it kept that one.
std::optional<std::string> thin_depth_note(std::string_view what, int asked, int kept,
                                           std::string_view setting);

}  // namespace slc
