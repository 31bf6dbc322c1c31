// Worker-thread count shared by all parallel loops (OpenMP underneath).
#include "slc/core/parallel.hpp"

#include <fmt/format.h>

#include <atomic>
#include <thread>

#include "slc/core/error.hpp"

namespace slc {
namespace {

int all_cores() {
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : static_cast<int>(n);
}

std::atomic<int> threads_in_use{all_cores()};

}  // namespace

void set_thread_count(int threads) {
    if (threads < 0) {
        throw InvalidInput(
            fmt::format("thread count must be 0 (all cores) or more, got {}", threads));
    }
    threads_in_use = threads == 0 ? all_cores() : threads;
}

int thread_count() { return threads_in_use; }

}  // namespace slc
