// The time loop: steps, vanishing, failures and the run's clocks.
#include "slc/evolve/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdint>
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

/// The process's CPU time (all threads) in whole nanoseconds: a difference of two readings is
/// exact, and seconds() of it the nearest double to the measured seconds.
std::int64_t process_cpu_ns() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

double seconds(std::int64_t ns) { return static_cast<double>(ns) / 1e9; }

void check(const RunOptions& o) {
    if (o.steps < 1) throw InvalidInput(fmt::format("steps must be at least 1, got {}", o.steps));
    if (!std::isfinite(o.t_start) || !std::isfinite(o.t_end) || !(o.t_end > o.t_start)) {
        throw InvalidInput(fmt::format("t-end must be finite and after the start time {}, got {}",
                                       o.t_start, o.t_end));
    }
}

/// The time after n of the N steps: from the step count, not by summing k, so that the last step
/// ends exactly at t_end and a resumed run takes the same steps.
double time_after(const RunOptions& o, int n) {
    const double k = (o.t_end - o.t_start) / o.steps;
    return n == o.steps ? o.t_end : o.t_start + n * k;
}

}  // namespace

RunResult run(const Interface& initial, const VelocityLaw& law, const Box& domain,
              const RunOptions& options, const Observer& observer) {
    RunResult start;  // resume() checks the options
    start.curves = initial;
    start.t = options.t_start;
    return resume(start, law, domain, options, observer);
}

RunResult resume(const RunResult& from, const VelocityLaw& law, const Box& domain,
                 const RunOptions& options, const Observer& observer) {
    check(options);
    if (from.steps_done < 0 || from.steps_done >= options.steps) {
        throw InvalidInput(fmt::format("cannot resume after step {} of a run of {} steps",
                                       from.steps_done, options.steps));
    }
    if (from.t != time_after(options, from.steps_done)) {
        throw InvalidInput(fmt::format("cannot resume: t = {} is not the time after step {} ({})",
                                       from.t, from.steps_done,
                                       time_after(options, from.steps_done)));
    }
    RunResult result = from;
    result.status = RunStatus::ok;
    result.message.clear();
    const double wall_before = from.wall_s;
    const double cpu_before = from.cpu_s;
    const auto wall_start = std::chrono::steady_clock::now();
    const std::int64_t cpu_start = process_cpu_ns();
    auto clocks = [&] {
        result.wall_s =
            wall_before +
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        result.cpu_s = cpu_before + seconds(process_cpu_ns() - cpu_start);
    };
    for (int n = from.steps_done + 1; n <= options.steps; ++n) {
        const double t_next = time_after(options, n);
        StepResult step;
        const std::int64_t step_cpu_start = process_cpu_ns();
        try {
            step = advance(result.curves, result.t, t_next - result.t, law, domain, options.step);
        } catch (const NumericalFailure& e) {
            result.status = RunStatus::error;
            result.message = fmt::format("step {} from t = {}: {}", n, result.t, e.what());
            break;
        }
        const double step_cpu_s = seconds(process_cpu_ns() - step_cpu_start);
        result.g_evals += step.stats.g_evals();
        result.vertices_produced += step.stats.vertices();
        result.curves = std::move(step.curves);
        result.t = t_next;
        result.steps_done = n;
        clocks();
        const bool go_on =
            !observer || observer(StepReport{n, options.steps, result.t, &result.curves,
                                             &step.stats, result.wall_s, step_cpu_s, &result});
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
