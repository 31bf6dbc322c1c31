// Worker-thread count shared by all parallel loops (OpenMP underneath).
#include "slc/core/parallel.hpp"

#include <fmt/format.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <thread>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// The threads of thread_count() 0: OMP_NUM_THREADS when it is set to a positive count (the
/// first of a list), else the cores; never more than the cores.
int default_threads() {
    const int cores = available_cores();
    if (const char* env = std::getenv("OMP_NUM_THREADS")) {
        char* end = nullptr;
        const long n = std::strtol(env, &end, 10);
        if (end != env && n > 0) return static_cast<int>(std::min<long>(n, cores));
    }
    return cores;
}

std::atomic<int> threads_in_use{default_threads()};

}  // namespace

int available_cores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : static_cast<int>(n);
}

void set_thread_count(int threads) {
    if (threads < 0) {
        throw InvalidInput(
            fmt::format("thread count must be 0 (all cores) or more, got {}", threads));
    }
    threads_in_use = threads == 0 ? default_threads() : std::min(threads, available_cores());
}

int thread_count() { return threads_in_use; }

}  // namespace slc
