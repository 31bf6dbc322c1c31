// Memory budgets: the cells of a tree refined along curves, and the machine's memory.
#include "commands/memory_budget.hpp"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "slc/core/error.hpp"

namespace slc::cli {
namespace {

/// Cells per level along a curve, per cell width of length: the refinement rule (split while
/// the edge exceeds the distance to Γ) keeps a band a few cells wide on either side of Γ.
constexpr double cells_per_width = 8.0;

/// InvalidInput, naming the deepest depth that fits, when `what` at `depth` would need more than
/// the memory this process may use: cells(d, size, width) × bytes_per_cell at depth d for the
/// trees `whose` describes, along curves of length (or a surface of area) `size` in a domain of
/// `width`.
void check_fits(const std::string& what, int depth, double size, double width,
                double bytes_per_cell, double (*cells)(int, double, double),
                const std::string& whose) {
    const double memory = static_cast<double>(physical_memory());
    if (!(memory > 0.0) || !(size > 0.0) || !(width > 0.0)) return;  // nothing to compare
    const auto bytes = [&](int d) { return cells(d, size, width) * bytes_per_cell; };
    if (bytes(depth) <= memory) return;
    int fits = depth;
    while (fits > 0 && bytes(fits) > memory) --fits;
    constexpr double gib = 1024.0 * 1024.0 * 1024.0;
    throw InvalidInput(
        fmt::format("{} would need about {:.3g} GiB for {}, more than the {:.3g} GiB of memory "
                    "this process may use; depth {} fits",
                    what, bytes(depth) / gib, whose, memory / gib, fits));
}

}  // namespace

double tree_cells(int depth, double length, double width) {
    double cells = 0.0;
    for (int l = 0; l <= depth; ++l) {
        const double along = cells_per_width * length * std::ldexp(1.0, l) / width;
        cells += std::min(std::ldexp(1.0, 2 * l), along);
    }
    return cells;
}

std::uint64_t physical_memory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page <= 0) return 0;
    std::uint64_t memory = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        memory = std::min<std::uint64_t>(memory, limit.rlim_cur);
    std::ifstream cgroup("/sys/fs/cgroup/memory.max");
    std::uint64_t cap = 0;
    if (cgroup >> cap && cap > 0) memory = std::min(memory, cap);  // "max" reads as no number
    return memory;
}

void check_tree_memory(const std::string& what, int depth, double length, double width,
                       double bytes_per_cell) {
    check_fits(what, depth, length, width, bytes_per_cell, tree_cells,
               fmt::format("its trees along curves of length {:.4g}", length));
}

double octree_cells(int depth, double area, double width) {
    double cells = 0.0;
    for (int l = 0; l <= depth; ++l) {
        const double h = width / std::ldexp(1.0, l);
        cells += std::min(std::ldexp(1.0, 3 * l), cells_per_width * area / (h * h));
    }
    return cells;
}

void check_octree_memory(const std::string& what, int depth, double area, double width,
                         double bytes_per_cell) {
    check_fits(what, depth, area, width, bytes_per_cell, octree_cells,
               fmt::format("its octree along a surface of area {:.4g}", area));
}

}  // namespace slc::cli
