// slc contour on a surface (DESIGN §8): the exact signed distance of a closed triangle surface,
// or a built-in implicit surface, contoured in space.
#pragma once

#include <optional>
#include <string>

#include "commands/common.hpp"

namespace slc::cli {

/// What `slc contour` was given, for a surface file or a built-in function.
struct SurfaceContourRequest {
    std::string initial;       ///< a surface file, or empty
    std::string function;      ///< a built-in implicit surface, or empty
    std::optional<int> depth;  ///< K; unset: depth_for_domain, as slc run takes for a surface
    int refine = 0;
    std::optional<double> eps;
    std::optional<double> eta;  ///< unset: contour_tolerances
    int thin_depth = 0;
    /// Whether --thin-depth was given: else, for a surface file, another thin depth is kept where
    /// the one asked for loses the surface's components or handles (keeping_topology).
    bool thin_depth_given = false;
    DomainOptions domain;
    std::optional<int> tree_depth;
    std::string out;
};

/// Contours, writes final.obj, final.vtp, final.png and summary.json (last) into out.
void run_surface_contour(const SurfaceContourRequest& request);

}  // namespace slc::cli
