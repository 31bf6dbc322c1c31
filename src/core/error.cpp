// The failure path of SLC_ASSERT: a broken invariant is a bug, reported as an exception so that
// tests can see it and the command-line tool can report it without losing files already written.
#include "slc/core/error.hpp"

#include <fmt/format.h>

namespace slc::detail {

void assertion_failed(const char* condition, const char* invariant, const char* file, int line) {
    throw std::logic_error(
        fmt::format("internal error: {} ({}) failed at {}:{}", invariant, condition, file, line));
}

}  // namespace slc::detail
