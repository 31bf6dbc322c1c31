/// @file
/// What a velocity law's exact motion keeps, or cannot do: the run loop checks every step against
/// it (evolve/guards.hpp), so that a run whose numerics fail says so instead of ending "ok".
#pragma once

#include <optional>

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
    /// Of a surface: dV/dt = rate × A while no component vanishes or merges (a constant normal
    /// speed: the rate is the speed).
    std::optional<double> volume_rate_per_area = std::nullopt;
};

}  // namespace slc
