/// @file
/// A request to stop a run soon, from a signal handler or another thread. The time loop and the
/// contours check it between the stages of a step (the distance, each contour, each pass of the
/// tree and of refinement), so that a long step stops within about a stage's time, not at its
/// end: the run then ends with status interrupted and the interface of its last whole step.
#pragma once

namespace slc {

/// Asks the computation under way to stop at its next check. Async-signal-safe.
void request_stop() noexcept;
/// Withdraws the request (before a new run).
void clear_stop() noexcept;
/// True while a stop is requested.
bool stop_requested() noexcept;

/// What check_stop() throws: caught by the time loop (status interrupted). Not a
/// std::exception, so that no handler of errors takes it for one.
struct StopRequested {};

/// Throws StopRequested when a stop is requested. Call it only outside parallel loops.
void check_stop();

}  // namespace slc
