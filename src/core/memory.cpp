// keep_freed_memory(): glibc's thresholds for returning freed memory to the system.
#include "slc/core/memory.hpp"

#include <cstdlib>  // any C library header: glibc's defines __GLIBC__, tested below
#include <new>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace slc {

bool keep_freed_memory() {
#if defined(__GLIBC__)
    // By default glibc maps blocks above a threshold (128 KiB, raised to the largest block freed
    // so far, at most 32 MiB) one by one and unmaps them when freed, and trims the heap once its
    // free top exceeds twice that threshold: every step then faults its arrays in afresh. No
    // block is mapped on its own (the largest arrays of a fine contour are hundreds of MiB), and
    // up to 2 GiB of free heap is kept.
    constexpr int trimmed_above = 2000 << 20;
    return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, trimmed_above) == 1;
#else
    return false;
#endif
}

void* allocate_huge(std::size_t bytes) {
    const std::size_t rounded = (bytes + huge_page_size - 1) / huge_page_size * huge_page_size;
    void* block = std::aligned_alloc(huge_page_size, rounded);
    if (block == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(block, rounded, MADV_HUGEPAGE);  // a hint: refused, the pages stay small
#endif
    return block;
}

void free_huge(void* block) noexcept { std::free(block); }

}  // namespace slc
