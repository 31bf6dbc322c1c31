/// @file
/// Errors: InvalidInput for bad input at a public entry point, and SLC_ASSERT for broken
/// invariants.
#pragma once

#include <stdexcept>
#include <string>

namespace slc {

/// Bad input at a public entry point. The message names the parameter and the value, in one line,
/// so that the command-line tool can print it as it is and exit with status 2.
class InvalidInput : public std::runtime_error {
public:
    /// what: the one-line message, naming the parameter and the value.
    explicit InvalidInput(const std::string& what) : std::runtime_error(what) {}
};

/// A computation that could not be completed for a reason that lies in the data (an ill-posed
/// contour, a curve leaving the domain), reported with the time and place.
class NumericalFailure : public std::runtime_error {
public:
    /// what: the one-line message, naming the time or the place.
    explicit NumericalFailure(const std::string& what) : std::runtime_error(what) {}
};

/// A setting asks for more than a limit allows (a contour refined to ε needing more vertices
/// than ContourOptions::max_vertices): smaller time steps would not help, the setting must change.
class LimitExceeded : public NumericalFailure {
public:
    /// what: the one-line message, naming the setting to change.
    explicit LimitExceeded(const std::string& what) : NumericalFailure(what) {}
};

/// The zero set of a contoured function reaches the edge of its domain: a larger domain would
/// hold it (the time loop may grow the domain and try again).
class LeftDomain : public NumericalFailure {
public:
    /// what: the one-line message, naming the place.
    explicit LeftDomain(const std::string& what) : NumericalFailure(what) {}
};

namespace detail {
[[noreturn]] void assertion_failed(const char* condition, const char* invariant, const char* file,
                                   int line);
}  // namespace detail

}  // namespace slc

/// Checks an invariant of the library (not of the user's input) in debug and test builds.
#if defined(SLC_ENABLE_ASSERTS) || !defined(NDEBUG)
#define SLC_ASSERT(cond, invariant)                                                         \
    do {                                                                                    \
        if (!(cond)) ::slc::detail::assertion_failed(#cond, invariant, __FILE__, __LINE__); \
    } while (false)
#else
// Off: the condition is not evaluated, but still compiled, so it stays valid code and the
// variables it names count as used.
#define SLC_ASSERT(cond, invariant) \
    do {                            \
        (void)sizeof(!(cond));      \
    } while (false)
#endif
