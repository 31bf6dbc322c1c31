#include "slc/core/parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
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

TEST(ParallelForCheap, RunsEveryIterationOnceOnAnyThreadCount) {
    const AllCoresAfterwards restore;
    for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        // Above cheap_grain (on all threads, one part a thread) and below it (on this thread).
        for (const std::size_t n : {cheap_grain * 3 + 7, cheap_grain / 2}) {
            std::vector<int> runs(n, 0);
            parallel_for_cheap(n, [&](std::size_t i) { ++runs[i]; });
            EXPECT_EQ(std::vector<int>(n, 1), runs) << threads << " threads, n " << n;
        }
    }
}

TEST(ParallelForCheap, ThrowsWhatTheLeastFailingIterationThrewOnAnyThreadCount) {
    const AllCoresAfterwards restore;
    const std::size_t n = 4 * cheap_grain;
    for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        try {
            parallel_for_cheap(n, [&](std::size_t i) {
                if (i == n / 3 || i == n / 2 || i == n - 1)
                    throw std::runtime_error("iteration " + std::to_string(i));
            });
            ADD_FAILURE() << "expected the body's exception on " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ("iteration " + std::to_string(n / 3), e.what()) << threads << " threads";
        }
    }
}

TEST(CountingSort, IsAStableSortByKeyOnAnyThreadCount) {
    const AllCoresAfterwards restore;
    const std::size_t n = 30001, buckets = 97;
    auto key = [](std::size_t i) { return (i * 7919 + i / 13) % 97; };
    std::vector<std::uint32_t> expected(n);
    for (std::size_t i = 0; i < n; ++i) expected[i] = static_cast<std::uint32_t>(i);
    std::stable_sort(expected.begin(), expected.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    for (int threads : {1, 2, 3}) {
        set_thread_count(threads);
        const Buckets got = counting_sort(n, buckets, key);
        EXPECT_EQ(expected, got.items) << threads << " threads";
        ASSERT_EQ(buckets + 1, got.start.size());
        for (std::size_t b = 0; b < buckets; ++b)
            for (std::uint32_t i = got.start[b]; i < got.start[b + 1]; ++i)
                EXPECT_EQ(b, key(got.items[i]));
    }
}

TEST(ParallelSort, GivesStdSortsOrderOnAnyThreadCount) {
    // Keys made unique by an index, as the precondition asks; many repeated codes, so the
    // merges meet ties of the code that the index breaks. Sizes below and above the cut-off,
    // and one that does not divide among the threads.
    const AllCoresAfterwards restore;
    for (const std::size_t n : {std::size_t{100}, std::size_t{50000}, std::size_t{50001}}) {
        std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
        std::uint64_t state = 12345;
        for (std::size_t i = 0; i < n; ++i) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            keys[i] = {state >> 54, static_cast<std::uint32_t>(i)};
        }
        auto expected = keys;
        std::sort(expected.begin(), expected.end());
        for (int threads : {1, 2, 3, 4}) {
            set_thread_count(threads);
            auto sorted = keys;
            parallel_sort(sorted.begin(), sorted.end());
            EXPECT_EQ(expected, sorted) << n << " keys, " << threads << " threads";
        }
    }
}

}  // namespace
}  // namespace slc
