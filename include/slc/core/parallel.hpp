/// @file
/// Parallel loops over batches. Every loop here writes each output slot from exactly one
/// iteration, and reductions are done afterwards in index order, so results never depend on the
/// number of threads.
#pragma once

#include <cstddef>

namespace slc {

/// Sets the number of worker threads for later parallel loops (0 = all cores).
/// Throws InvalidInput for a negative count.
void set_thread_count(int threads);

/// The number of worker threads parallel loops use.
int thread_count();

/// Below this many iterations a loop runs on the calling thread: starting threads costs more.
inline constexpr std::size_t parallel_grain = 256;
/// The same for loops whose every iteration costs a microsecond or more (an evaluation of G, a
/// closest-point query): there, 32 iterations already repay starting the threads.
inline constexpr std::size_t expensive_grain = 32;

/// Calls body(i) for i in [0, n), on all worker threads when n >= min_iterations (for loops
/// whose iterations are each long, pass fewer than parallel_grain). body must only write data
/// owned by iteration i.
template <class Body>
void parallel_for(std::size_t n, Body&& body, std::size_t min_iterations = parallel_grain) {
    if (n < min_iterations || n < 2 || thread_count() == 1) {
        for (std::size_t i = 0; i < n; ++i) body(i);
        return;
    }
    const long long count = static_cast<long long>(n);
#pragma omp parallel for schedule(static) num_threads(thread_count())
    for (long long i = 0; i < count; ++i) body(static_cast<std::size_t>(i));
}

}  // namespace slc
