// The stop request: one lock-free flag.
#include "slc/core/stop.hpp"

#include <atomic>

namespace slc {
namespace {

std::atomic<bool> requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler sets the flag");

}  // namespace

void request_stop() noexcept { requested.store(true, std::memory_order_relaxed); }

void clear_stop() noexcept { requested.store(false, std::memory_order_relaxed); }

bool stop_requested() noexcept { return requested.load(std::memory_order_relaxed); }

void check_stop() {
    if (stop_requested()) throw StopRequested{};
}

}  // namespace slc
