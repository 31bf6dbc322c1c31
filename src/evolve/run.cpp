// The time loop: steps, vanishing, failures and the run's clocks.
#include "slc/evolve/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <ctime>

#include "slc/core/error.hpp"

namespace slc {

const char* to_string(RunStatus status) {
    switch (status) {
        case RunStatus::ok:
            return "ok";
        case RunStatus::vanished:
            return "vanished";
        case RunStatus::interrupted:
            return "interrupted";
        default:
            return "error";
    }
}

namespace {

double process_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void check(const RunOptions& o) {
    if (o.steps < 1) throw InvalidInput(fmt::format("steps must be at least 1, got {}", o.steps));
    if (!std::isfinite(o.t_start) || !std::isfinite(o.t_end) || !(o.t_end > o.t_start)) {
        throw InvalidInput(fmt::format("t-end must be finite and after the start time {}, got {}",
                                       o.t_start, o.t_end));
    }
}

}  // namespace

RunResult run(const Interface& initial, const VelocityLaw& law, const Box& domain,
              const RunOptions& options, const Observer& observer) {
    check(options);
    RunResult result;
    result.curves = initial;
    result.t = options.t_start;
    const double k = (options.t_end - options.t_start) / options.steps;
    const auto wall_start = std::chrono::steady_clock::now();
    const double cpu_start = process_cpu_seconds();
    auto clocks = [&] {
        result.wall_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        result.cpu_s = process_cpu_seconds() - cpu_start;
    };
    for (int n = 1; n <= options.steps; ++n) {
        // t from the step count, not by summing k, so that the last step ends exactly at t_end.
        const double t_next = n == options.steps ? options.t_end : options.t_start + n * k;
        StepResult step;
        try {
            step = advance(result.curves, result.t, t_next - result.t, law, domain, options.step);
        } catch (const NumericalFailure& e) {
            result.status = RunStatus::error;
            result.message = fmt::format("step {} from t = {}: {}", n, result.t, e.what());
            break;
        }
        result.g_evals += step.stats.g_evals();
        result.vertices_produced += step.stats.vertices();
        result.curves = std::move(step.curves);
        result.t = t_next;
        result.steps_done = n;
        clocks();
        const bool go_on =
            !observer || observer(StepReport{n, options.steps, result.t, &result.curves,
                                             &step.stats, result.wall_s});
        if (result.curves.empty()) {
            result.status = RunStatus::vanished;
            break;
        }
        if (!go_on && n < options.steps) {
            result.status = RunStatus::interrupted;
            break;
        }
    }
    clocks();
    return result;
}

}  // namespace slc
