// keep_freed_memory(): glibc's thresholds for returning freed memory to the system.
#include "slc/core/memory.hpp"

#include <cstdlib>  // any C library header: glibc's defines __GLIBC__, tested below

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace slc {

bool keep_freed_memory() {
#if defined(__GLIBC__)
    // By default glibc maps blocks above a threshold (128 KiB, raised to the largest block freed
    // so far) one by one and unmaps them when freed, and trims the heap once its free top
    // exceeds twice that threshold: every step then faults its arrays in afresh.
    constexpr int mapped_above = 32 << 20;
    constexpr int trimmed_above = 256 << 20;
    return mallopt(M_MMAP_THRESHOLD, mapped_above) == 1 &&
           mallopt(M_TRIM_THRESHOLD, trimmed_above) == 1;
#else
    return false;
#endif
}

}  // namespace slc
