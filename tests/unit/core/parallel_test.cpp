#include "slc/core/parallel.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace slc {
namespace {

/// Restores all cores however a test ends.
struct AllCoresAfterwards {
    ~AllCoresAfterwards() { set_thread_count(0); }
};

TEST(ParallelFor, RunsEveryIterationOnceOnAnyThreadCount) {
    const AllCoresAfterwards restore;
    for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        std::vector<int> runs(10000, 0);
        parallel_for(runs.size(), [&](std::size_t i) { ++runs[i]; });
        EXPECT_EQ(std::vector<int>(runs.size(), 1), runs) << threads << " threads";
    }
}

TEST(ParallelFor, ThrowsWhatTheLeastFailingIterationThrewOnAnyThreadCount) {
    // Iterations fail in both halves of the loop, so on two threads both throw; the exception
    // must reach the caller (not end the process) and be the one a loop on one thread meets.
    const AllCoresAfterwards restore;
    for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        try {
            parallel_for(10000, [](std::size_t i) {
                if (i == 3000 || i == 7000 || i == 9999)
                    throw std::runtime_error("iteration " + std::to_string(i));
            });
            ADD_FAILURE() << "expected the body's exception on " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string("iteration 3000"), e.what()) << threads << " threads";
        }
    }
}

TEST(ParallelFor, AFailureOnlyLateInTheLoopIsStillThrown) {
    const AllCoresAfterwards restore;
    set_thread_count(2);
    EXPECT_THROW(parallel_for(1000,
                              [](std::size_t i) {
                                  if (i == 999) throw std::logic_error("last");
                              }),
                 std::logic_error);
}

}  // namespace
}  // namespace slc
