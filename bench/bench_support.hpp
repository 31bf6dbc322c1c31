// What the benchmark programs share: a reporter that keeps every run so that a program can write
// its markdown tables after the console report, CPU seconds of a run, and flags of the program's
// own taken out of argv before Google Benchmark parses the rest. The regions a program writes
// into a page written by hand: doc_regions.hpp.
#pragma once

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace slc::bench {

/// CPU seconds per iteration of a run.
inline double seconds(const benchmark::BenchmarkReporter::Run& r) {
    return r.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(r.time_unit);
}

/// Keeps, by benchmark name ("BM_BuildTree/12"), the iteration run of least CPU time per
/// iteration: with --benchmark_repetitions=n and --benchmark_enable_random_interleaving=true
/// (as scripts/bench runs them), the least of n repetitions spread over the program's run, so
/// that a slower spell of the machine slows at most some of them.
class Recorder : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& r : runs) {
            if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
            const auto [it, added] = results.try_emplace(r.benchmark_name(), r);
            if (!added && seconds(r) < seconds(it->second)) it->second = r;
        }
        ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, Run> results;
};

/// Seconds of the steady clock, for wall times.
inline double wall_now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

/// Removes `--flag value` from argv and returns value, or fallback.
inline std::string take_flag(int& argc, char** argv, const char* flag, std::string fallback) {
    for (int i = 1; i + 1 < argc; ++i) {
        if (std::strcmp(argv[i], flag) == 0) {
            std::string value = argv[i + 1];
            for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
            argc -= 2;
            return value;
        }
    }
    return fallback;
}

/// Removes `--flag` from argv and returns whether it was there.
inline bool take_switch(int& argc, char** argv, const char* flag) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], flag) == 0) {
            for (int j = i; j + 1 <= argc; ++j) argv[j] = argv[j + 1];
            argc -= 1;
            return true;
        }
    }
    return false;
}

}  // namespace slc::bench
