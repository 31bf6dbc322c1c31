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
    DomainOptions domain;
    std::optional<int> tree_depth;
    std::string out;
};

/// Contours, writes final.obj, final.vtp, final.png and summary.json (last) into out.
void run_surface_contour(const SurfaceContourRequest& request);

}  // namespace slc::cli
