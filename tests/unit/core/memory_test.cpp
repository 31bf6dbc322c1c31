#include "slc/core/memory.hpp"

#include <gtest/gtest.h>

#include <cstdint>
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

TEST(AllocateHuge, GivesAlignedBlocksThatHoldWhatIsWritten) {
    // Sizes at, between and beyond multiples of the huge page: each block aligned to it, every
    // byte of it usable.
    for (const std::size_t bytes :
         {huge_page_size, huge_page_size + 8, 3 * huge_page_size - 8, 5 * huge_page_size}) {
        auto* block = static_cast<unsigned char*>(allocate_huge(bytes));
        ASSERT_NE(block, nullptr);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(block) % huge_page_size, 0u);
        for (std::size_t i = 0; i < bytes; ++i) block[i] = static_cast<unsigned char>(i * 7);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < bytes; ++i)
            wrong += block[i] != static_cast<unsigned char>(i * 7) ? 1 : 0;
        EXPECT_EQ(wrong, 0u);
        free_huge(block);
    }
}

}  // namespace
}  // namespace slc
