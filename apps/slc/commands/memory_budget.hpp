// Memory budgets of the trees a command builds, estimated before it builds them, so that a depth
// the machine cannot hold is refused with the figure instead of exhausting memory.
#pragma once

#include <cstdint>
#include <string>

namespace slc::cli {

/// Bytes per estimated cell (tree_cells) of what a command holds at its peak, measured on the
/// release build as peak resident memory over tree_cells and rounded up by a third or more: slc
/// distance (the distance tree: 31 at L = 18), slc contour (the contouring tree, its statistics
/// and the picture of its cells: 4600 at K = 12 and 14), and a step of slc run (its distance and
/// contouring trees: 275 at K = 12).
inline constexpr double distance_bytes_per_cell = 40.0;
inline constexpr double contour_bytes_per_cell = 6000.0;
inline constexpr double run_bytes_per_cell = 400.0;
/// slc contour on a surface: the octree, its tetrahedra (24 or more a leaf) and G at their
/// vertices. Provisional, from the sizes of the arrays: not yet measured as peak memory.
inline constexpr double surface_contour_bytes_per_cell = 1500.0;

/// Cells of a quadtree refined to `depth` along curves of total length `length` in a square
/// domain of width `width`: at level l about cells_per_width · length / (width / 2^l) cells (those
/// near the curves), at most 4^l, summed over the levels.
double tree_cells(int depth, double length, double width);

/// The memory this process may use, in bytes: the machine's (sysconf: physical pages × page
/// size), or less under a limit of its address space (ulimit -v) or of its cgroup (memory.max).
std::uint64_t physical_memory();

/// Throws InvalidInput naming `what` ("--tree-depth 22"), the estimate, the memory and the largest
/// depth that fits, when the tree (tree_cells × bytes_per_cell) would take more than
/// physical_memory().
void check_tree_memory(const std::string& what, int depth, double length, double width,
                       double bytes_per_cell);

/// Cells of an octree refined to `depth` along a surface of area `area` in a cubic domain of
/// width `width`: at level l about cells_per_width · area / h² cells (h the level's edge), at
/// most 8^l, summed over the levels.
double octree_cells(int depth, double area, double width);

/// As check_tree_memory, for an octree along a surface of the given area.
void check_octree_memory(const std::string& what, int depth, double area, double width,
                         double bytes_per_cell);

}  // namespace slc::cli
