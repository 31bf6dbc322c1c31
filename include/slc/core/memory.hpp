/// @file
/// How the process hands freed memory back to the system: a time loop frees and allocates the
/// same large arrays every step (trees, tables of samples, meshes); and blocks on huge pages for
/// tables read at random.
#pragma once

#include <cstddef>

namespace slc {

/// Keeps memory a step frees in the process for the next step, instead of returning it to the
/// system and taking it back a page fault at a time: with glibc, every block comes from the heap
/// (none is mapped on its own) and up to 2 GiB of free heap is kept. Call once, at the start of a
/// program that runs many steps; it changes how much memory the process holds, never a result. Does
/// nothing with other C libraries, or under AddressSanitizer's allocator. Returns whether the
/// settings were taken.
bool keep_freed_memory();

/// The size from which allocate_huge() asks for huge pages: 2 MiB.
inline constexpr std::size_t huge_page_size = std::size_t{2} << 20;
/// A block of at least `bytes` (≥ huge_page_size) aligned to huge_page_size and offered to the
/// kernel as huge pages (Linux's madvise; elsewhere, or where the kernel declines, plain pages):
/// a table of millions of entries read at random then misses the TLB far less often. Throws
/// std::bad_alloc. Freed by free_huge().
void* allocate_huge(std::size_t bytes);
/// Frees a block of allocate_huge().
void free_huge(void* block) noexcept;

}  // namespace slc
