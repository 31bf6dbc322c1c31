#include "slc/core/memory.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace slc {
namespace {

TEST(KeepFreedMemory, IsTakenByGlibcAndChangesNoResult) {
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer's allocator stands in for glibc's and takes no settings.
    EXPECT_FALSE(keep_freed_memory());
#elif defined(__GLIBC__)
    EXPECT_TRUE(keep_freed_memory());
#else
    EXPECT_FALSE(keep_freed_memory());
#endif
    // Large blocks allocated, freed and allocated again still hold what is written to them.
    for (int round = 0; round < 3; ++round) {
        std::vector<double> block(std::size_t{1} << 22);
        std::iota(block.begin(), block.end(), static_cast<double>(round));
        EXPECT_EQ(block.back(), static_cast<double>(round) + static_cast<double>(block.size() - 1));
    }
}

}  // namespace
}  // namespace slc
