#pragma once
// How the process's allocator treats large blocks, for programs that hold volumes.
#include <cstddef>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace cutaway {

/// Has glibc map every block of 8 MiB or more on its own, and unmap it when
/// it is freed. By default glibc raises that threshold to the largest block
/// freed so far (up to 32 MiB) and serves later blocks of that size from the
/// heap, which keeps them resident after they are freed: an upload's staging
/// buffer, a label volume's class bytes and lavapipe's device memory (process
/// memory) stayed in the peak of a frog_labels render, about 30 MB of it.
/// Smaller blocks (a 512x512 frame's pixels, 4 MiB) stay in the heap and are
/// reused from frame to frame without page faults.
/// Call once at the start of main. Does nothing on other C libraries.
inline void unmapLargeBlocksWhenFreed() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 8 << 20);
#endif
}

} // namespace cutaway
