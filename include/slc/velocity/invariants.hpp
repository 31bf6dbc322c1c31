/// @file
/// What a velocity law's exact motion keeps, or cannot do: the run loop checks every step against
/// it (evolve/guards.hpp), so that a run whose numerics fail says so instead of ending "ok".
#pragma once

#include <optional>

#include "slc/core/vec2.hpp"

namespace slc {

/// A law's invariants; the default claims nothing.
struct Invariants {
    /// The enclosed area is conserved: rigid motions, divergence-free flows, the
    /// volume-preserving flow. The curves cannot vanish.
    bool keeps_area = false;
    /// Every curve keeps its shape (rotation, translation, no motion): the number of curves
    /// cannot change.
    bool rigid = false;
    /// No curve can split into several (curvature flow of embedded curves, rigid motions).
    bool cannot_split = false;
    /// The enclosed region only grows, so its area cannot fall and the curves cannot vanish: a
    /// normal speed positive for every point and direction. Its parts can merge, but none can
    /// split off.
    bool cannot_vanish = false;
    /// The enclosed region only shrinks: a normal speed negative for every point and direction.
    /// Its holes (cavities) can merge with each other or open to the outside, but none can
    /// appear or split.
    bool cannot_grow = false;
    /// The total length cannot grow: curvature flow and the area-preserving curvature flow,
    /// gradient flows of length. Noise that roughens the curves breaks it first.
    bool shortens = false;
    /// dA/dt = rate × (counterclockwise curves − clockwise ones) while no curve vanishes
    /// (curvature flow of embedded curves: −2π).
    std::optional<double> area_rate_per_curve = std::nullopt;
    /// dA/dt = rate for the whole interface (a source injecting at the rate: hele-shaw's Q); the
    /// step's area correction (VelocityLaw::preserves_area) then restores A(t) + k·rate.
    std::optional<double> area_rate = std::nullopt;
    /// Each region (an outer curve and its holes, curve_regions) keeps its own area, not only
    /// their sum, while the regions neither merge nor vanish (hele-shaw's bubbles); with
    /// area_rate, the region holding area_source grows at it. The step's area correction then
    /// restores each region's area.
    bool keeps_region_areas = false;
    /// Where area_rate enters (hele-shaw's source), for keeps_region_areas.
    std::optional<Vec2> area_source = std::nullopt;
    /// Of a surface: dV/dt = rate × A while no component vanishes or merges (a constant normal
    /// speed: the rate is the speed).
    std::optional<double> volume_rate_per_area = std::nullopt;
};

/// What a constant normal speed s keeps, in dimension dim (unit-normal, a speed expression that
/// reads no variable): at 0 nothing moves; s > 0 only grows the region and s < 0 only shrinks it;
/// a surface's volume changes at s times its area.
template <int dim>
Invariants constant_speed_invariants(double s) {
    if (s == 0.0) return {.keeps_area = true, .rigid = true};
    Invariants kept{.cannot_vanish = s > 0.0, .cannot_grow = s < 0.0};
    if constexpr (dim == 3) kept.volume_rate_per_area = s;
    return kept;
}

}  // namespace slc
