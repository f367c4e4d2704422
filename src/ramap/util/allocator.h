// How the C library's allocator treats the memory the process frees.
#pragma once

namespace ramap {

// Asks glibc's malloc to keep freed blocks below 32 MiB in its heap, and up to 64 MiB free at the
// heap's top, for the next allocation, rather than handing them back to the kernel. Translation
// averaging and bundle adjustment allocate and free buffers of a few MiB in every iteration;
// handed back, each one is faulted in again page by page, which cost a run a noticeable share of
// its time (docs/benchmark-history.md, "Memory handed back to the kernel"). glibc's own adaptive
// thresholds may reach the same values, but only after a large block has been freed. No effect
// with another C library. For the command-line program only: a library leaves its host's
// allocator alone.
void KeepFreedMemoryForReuse();

}  // namespace ramap
