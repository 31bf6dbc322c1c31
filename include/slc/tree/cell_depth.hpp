/// @file
/// How deep a tree over a root box may go before doubles stop resolving its cells: the one rule
/// the quadtree and the octree share (the root's width and its largest coordinate decide, not
/// its dimension).
#pragma once

namespace slc {

/// The deepest level l <= cap with width·2^-l >= tolerance::min_relative_cell · magnitude, or −1
/// when width is outside [tolerance::min_domain_width, 2·tolerance::max_coordinate] or magnitude
/// beyond tolerance::max_coordinate (or either is NaN). width: the root's edge; magnitude: the
/// largest magnitude of a root corner coordinate.
int resolvable_depth(double width, double magnitude, int cap);

}  // namespace slc
