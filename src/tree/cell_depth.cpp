// The deepest resolvable level of a tree, shared by the quadtree and the octree.
#include "slc/tree/cell_depth.hpp"

#include <cmath>

#include "slc/core/tolerances.hpp"

namespace slc {

int resolvable_depth(double width, double magnitude, int cap) {
    if (!(width >= tolerance::min_domain_width) || !(magnitude <= tolerance::max_coordinate))
        return -1;
    // Cells halve with each level: the deepest l with w 2^-l ≥ min_relative_cell · magnitude.
    int depth = 0;
    while (depth < cap &&
           std::ldexp(width, -(depth + 1)) >= tolerance::min_relative_cell * magnitude) {
        ++depth;
    }
    return depth;
}

}  // namespace slc
