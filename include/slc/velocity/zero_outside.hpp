/// @file
/// A flow field known only in a box (a lattice, an OpenVDB grid) taken as zero outside it, for
/// fields that are zero there in fact: a flow computed in a box with still fluid around it.
#pragma once

#include <memory>

#include "slc/velocity/velocity.hpp"

namespace slc {

/// The flow field law, zero outside law.extent() and law's own field inside it (its closed box).
/// The result is known everywhere (no extent), so a run no longer refuses an interface that
/// leaves the box: what leaves it stops there. The field jumps to zero across the box's faces
/// unless law's is zero there. Its name is law's with " (zero outside)"; it claims none of law's
/// invariants. Throws InvalidInput, naming the law, for a law that is not a flow field or has no
/// extent.
template <int dim>
std::unique_ptr<BasicVelocityLaw<dim>> zero_outside_extent(
    std::unique_ptr<BasicVelocityLaw<dim>> law);

extern template std::unique_ptr<BasicVelocityLaw<2>> zero_outside_extent(
    std::unique_ptr<BasicVelocityLaw<2>>);
extern template std::unique_ptr<BasicVelocityLaw<3>> zero_outside_extent(
    std::unique_ptr<BasicVelocityLaw<3>>);

}  // namespace slc
