/// @file
/// How the process hands freed memory back to the system: a time loop frees and allocates the
/// same large arrays every step (trees, tables of samples, meshes).
#pragma once

namespace slc {

/// Keeps memory a step frees in the process for the next step, instead of returning it to the
/// system and taking it back a page fault at a time: with glibc, blocks up to 32 MiB come from
/// the heap and up to 256 MiB of free heap is kept. Call once, at the start of a program that
/// runs many steps; it changes how much memory the process holds, never a result. Does nothing
/// with other C libraries, or under AddressSanitizer's allocator. Returns whether the settings
/// were taken.
bool keep_freed_memory();

}  // namespace slc
