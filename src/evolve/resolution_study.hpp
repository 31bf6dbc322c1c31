// The runs of a self-convergence study, written once for curves and surfaces (internal to
// evolve): self_convergence.cpp (dim 2) and surface_study.cpp (dim 3) say how a level's options
// are made and how a run starts.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "slc/evolve/self_convergence.hpp"

namespace slc::detail {

/// A self-convergence study of `resolutions` levels: the options of every level r first
/// (options_at(r)), so that a level out of range fails before any run; then the run of each,
/// coarsest first (run_at(options)), the observer told after each; then the distances of
/// neighbours (final_distance), the observed orders and the estimate. Throws InvalidInput for
/// resolutions outside 3..5 (check_resolutions).
template <class Options, class Result, class OptionsAt, class RunAt>
BasicSelfConvergenceResult<BasicResolutionRun<Options, Result>> resolution_study(
    int resolutions, OptionsAt options_at, RunAt run_at,
    const std::function<void(const BasicResolutionRun<Options, Result>&)>& observer) {
    check_resolutions(resolutions);
    std::vector<Options> options;
    for (int r = 0; r < resolutions; ++r) options.push_back(options_at(r));

    BasicSelfConvergenceResult<BasicResolutionRun<Options, Result>> out;
    for (int r = 0; r < resolutions; ++r) {
        const Options& o = options[static_cast<std::size_t>(r)];
        BasicResolutionRun<Options, Result> run_r{r, o, run_at(o)};
        if (observer) observer(run_r);
        out.runs.push_back(std::move(run_r));
    }
    for (std::size_t r = 0; r + 1 < out.runs.size(); ++r)
        out.distances.push_back(final_distance(out.runs[r].result, out.runs[r + 1].result));
    observe_orders(out.distances, out.orders, out.estimate);
    return out;
}

}  // namespace slc::detail
