/// @file
/// The thin depth that keeps a user's shape (written once for curves and surfaces): the order in
/// which a run's start, slc contour and the Python package try the thin depths, and the contour
/// that keeps the shape's components and holes.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "slc/core/error.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/evolve/overrides.hpp"

namespace slc {

/// What trying one thin depth told a search of them (thin_depth_search).
enum class ThinDepthTry {
    keeps,        ///< the contour there keeps the shape: the search ends
    differs,      ///< it does not: try the next
    stop_deeper,  ///< it does not, and deeper cells will not either (they changed nothing more
                  ///< than the depth before, or failed): try no deeper one
};

/// The order in which the thin depths of a user's shape are tried, written once for a run's
/// start and for a contour (start_as_given, keeping_topology): the one `asked` first; then the
/// shallower ones, deepest first (thin cells following a sharp edge or point of the shape, which
/// is thinner than any cell near it, catch it unevenly: a convex pyramid in a general turn gets
/// handles beside its edges and specks at its apex at thin depths 1 to 8, none at 0); then, when
/// `asked` > 0, deeper ones two levels at a time up to setting_range's most, as a wall thinner
/// than the cells wants, until an attempt says stop_deeper. Returns the first depth whose
/// `attempt(thin)` keeps the shape, or nothing.
template <class Attempt>
std::optional<int> thin_depth_search(int asked, Attempt attempt) {
    if (attempt(asked) == ThinDepthTry::keeps) return asked;
    for (int shallower = asked - 1; shallower >= 0; --shallower)
        if (attempt(shallower) == ThinDepthTry::keeps) return shallower;
    for (int thin = asked; asked > 0 && thin < setting_range::thin_depth.hi;) {
        thin = std::min(thin + 2, setting_range::thin_depth.hi);
        const ThinDepthTry tried = attempt(thin);
        if (tried == ThinDepthTry::keeps) return thin;
        if (tried == ThinDepthTry::stop_deeper) break;
    }
    return std::nullopt;
}

/// A contour of a user's shape at the thin depth that keeps the shape's components and holes,
/// where one does: `at(thin)` contours at that thin depth, `topology_of` tells a contour's. The
/// depths in thin_depth_search's order; one whose contour fails (as where G vanishes along a
/// knife edge) keeps none, and none deeper is tried; nor deeper than one whose topology is the
/// depth's before (thinner than any cell). Returns the thin depth kept and its contour: the one
/// asked for and its contour when none keeps the shape.
template <class At, class TopologyOf>
auto keeping_topology(const ShapeTopology& given, int asked, At at, TopologyOf topology_of) {
    using Contour = decltype(at(asked));
    std::optional<Contour> first, kept;
    ShapeTopology before;  // the topology one depth up, from `asked` down the deeper ones
    const auto attempt = [&](int thin) {
        if (thin == asked) {
            first = at(asked);
            before = topology_of(*first);
            return before == given ? ThinDepthTry::keeps : ThinDepthTry::differs;
        }
        try {
            kept = at(thin);
        } catch (const NumericalFailure&) {
            return thin < asked ? ThinDepthTry::differs : ThinDepthTry::stop_deeper;
        }
        const ShapeTopology got = topology_of(*kept);
        if (got == given) return ThinDepthTry::keeps;
        if (thin < asked) return ThinDepthTry::differs;
        return std::exchange(before, got) == got ? ThinDepthTry::stop_deeper
                                                 : ThinDepthTry::differs;
    };
    const std::optional<int> thin = thin_depth_search(asked, attempt);
    if (thin && *thin != asked) return std::pair{*thin, std::move(*kept)};
    return std::pair{asked, std::move(*first)};
}

/// The note when keeping_topology kept another thin depth than the one asked for, naming the
/// setting as the caller does (`--thin-depth`, `thin_depth`); nothing when it kept that one.
std::optional<std::string> thin_depth_note(std::string_view what, int asked, int kept,
                                           std::string_view setting);

}  // namespace slc
