/// @file
/// Parallel loops over batches. Every loop here writes each output slot from exactly one
/// iteration, and reductions are done afterwards in index order, so results never depend on the
/// number of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <iterator>
#include <utility>
#include <vector>

namespace slc {

/// The cores this process may run on: its CPU affinity (taskset, a container's cpuset), or the
/// machine's when that is unknown.
int available_cores();

/// Sets the number of worker threads for later parallel loops: 0, the default, takes
/// OMP_NUM_THREADS when the environment sets it, else every available core; a count beyond the
/// available cores takes those (more threads than cores only wait on each other). The results
/// are the same for any count. Throws InvalidInput for a negative count.
void set_thread_count(int threads);

/// The number of worker threads parallel loops use.
int thread_count();

/// Below this many iterations a loop runs on the calling thread: starting threads costs more.
inline constexpr std::size_t parallel_grain = 256;
/// The same for loops whose every iteration is a few arithmetic operations on a few numbers
/// (parallel_for_cheap): below this many, waking the other threads costs more than the loop.
inline constexpr std::size_t cheap_grain = std::size_t{1} << 14;
/// The same for loops whose every iteration costs a microsecond or more (an evaluation of G, a
/// closest-point query): there, 32 iterations already repay starting the threads.
inline constexpr std::size_t expensive_grain = 32;

/// Calls body(i) for i in [0, n), on all worker threads when n >= min_iterations (for loops
/// whose iterations are each long, pass fewer than parallel_grain). body must only write data
/// owned by iteration i.
///
/// If body throws, parallel_for throws what body(i) threw for the least such i, as a loop on one
/// thread would: the exception never escapes a worker thread, and which one arrives does not
/// depend on the thread count. Iterations after the least failing one seen so far are skipped.
template <class Body>
void parallel_for(std::size_t n, Body&& body, std::size_t min_iterations = parallel_grain) {
    if (n < min_iterations || n < 2 || thread_count() == 1) {
        for (std::size_t i = 0; i < n; ++i) body(i);
        return;
    }
    const long long count = static_cast<long long>(n);
    // Chunks handed out as threads come free: iterations near a surface cost many times those
    // far from it, and halves fixed in advance leave one thread waiting on the other. Sixteen
    // chunks a thread at least, so that the last chunk is a small wait, and at most 64
    // iterations a chunk.
    const int threads = thread_count();
    const int chunk = static_cast<int>(std::clamp<long long>(count / (16LL * threads), 1, 64));
    std::atomic<long long> first_failure{count};
    std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads)
    for (long long i = 0; i < count; ++i) {
        if (i > first_failure.load(std::memory_order_relaxed)) continue;
        try {
            body(static_cast<std::size_t>(i));
        } catch (...) {
#pragma omp critical(slc_parallel_for_failure)
            if (i < first_failure.load(std::memory_order_relaxed)) {
                first_failure.store(i, std::memory_order_relaxed);
                failure = std::current_exception();
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
}

/// parallel_for for loops whose every iteration is a few arithmetic operations on a few numbers,
/// bound by memory: one contiguous part of [0, n) a thread, each in order, and on the calling
/// thread alone below cheap_grain. Chunks handed out as threads come free, as parallel_for hands
/// them, interleave the threads' memory and make such a loop slower on two threads than on one.
/// The same contract: body(i) writes only what iteration i owns, and the exception thrown is the
/// one of the least failing i.
template <class Body>
void parallel_for_cheap(std::size_t n, Body&& body) {
    const auto parts = static_cast<std::size_t>(std::max(1, thread_count()));
    if (n < cheap_grain || parts == 1) {
        for (std::size_t i = 0; i < n; ++i) body(i);
        return;
    }
    parallel_for(
        parts,
        [&](std::size_t p) {
            for (std::size_t i = n * p / parts; i < n * (p + 1) / parts; ++i) body(i);
        },
        1);
}

/// Items 0 to n − 1 sorted into `buckets` buckets by key(i) < buckets: bucket b holds
/// items[start[b]] to items[start[b + 1] − 1], in increasing order.
struct Buckets {
    std::vector<std::uint32_t> start;  ///< buckets + 1 offsets
    std::vector<std::uint32_t> items;  ///< n items
};

/// The counting sort of Buckets on all worker threads, in parts of the items, one a thread: each
/// part counts its items by bucket, then fills its own slots of each bucket after the parts
/// before it, so the result is the same for any number of threads. key must be safe to call
/// from several threads at once. O(n + buckets · threads).
template <class Key>
Buckets counting_sort(std::size_t n, std::size_t buckets, Key&& key) {
    const auto parts = static_cast<std::size_t>(std::max(1, thread_count()));
    std::vector<std::vector<std::uint32_t>> fill(parts, std::vector<std::uint32_t>(buckets, 0));
    parallel_for(
        parts,
        [&](std::size_t p) {
            for (std::size_t i = n * p / parts; i < n * (p + 1) / parts; ++i) ++fill[p][key(i)];
        },
        1);
    Buckets out;
    out.start.assign(buckets + 1, 0);
    for (std::size_t b = 0; b < buckets; ++b) {
        std::uint32_t at = out.start[b];
        for (std::size_t p = 0; p < parts; ++p) std::swap(at, fill[p][b]), at += fill[p][b];
        out.start[b + 1] = at;
    }
    out.items.resize(n);
    parallel_for(
        parts,
        [&](std::size_t p) {
            for (std::size_t i = n * p / parts; i < n * (p + 1) / parts; ++i)
                out.items[fill[p][key(i)]++] = static_cast<std::uint32_t>(i);
        },
        1);
    return out;
}

/// Sorts [first, last) by `less` on all worker threads: each thread sorts a part with std::sort,
/// then the parts are merged in rounds of pairs. Precondition: no two elements are equivalent
/// under `less` (keys made unique, say by an index), so the order is the one std::sort gives,
/// whatever the number of threads.
template <class It, class Less = std::less<>>
void parallel_sort(It first, It last, Less less = {}) {
    const auto n = static_cast<std::size_t>(std::distance(first, last));
    const auto parts = static_cast<std::size_t>(std::max(1, thread_count()));
    if (parts == 1 || n < 4096) {
        std::sort(first, last, less);
        return;
    }
    auto at = [&](std::size_t part) {
        return first + static_cast<std::ptrdiff_t>(n * part / parts);
    };
    parallel_for(
        parts, [&](std::size_t p) { std::sort(at(p), at(p + 1), less); }, 1);
    for (std::size_t width = 1; width < parts; width *= 2) {
        parallel_for((parts + 2 * width - 1) / (2 * width),
                     [&](std::size_t pair) {
                         const std::size_t lo = 2 * width * pair, mid = lo + width;
                         if (mid < parts)
                             std::inplace_merge(at(lo), at(mid), at(std::min(parts, mid + width)),
                                                less);
                     },
                     1);
    }
}

}  // namespace slc
