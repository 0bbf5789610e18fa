#pragma once
// How the process's allocator treats large blocks, for programs that hold volumes.
#include <cstddef>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace cutaway {

/// Blocks of this size or more are mapped on their own (below).
inline constexpr int kMappedBlockBytes = 8 << 20;

/// Has glibc map every block of 8 MiB or more on its own, and unmap it when
/// it is freed. By default glibc raises that threshold to the largest block
/// freed so far (up to 32 MiB) and serves later blocks of that size from the
/// heap, which keeps them resident after they are freed: an upload's staging
/// buffer, a label volume's class bytes and lavapipe's device memory (process
/// memory) stayed in the peak of a frog_labels render, about 30 MB of it.
/// Smaller blocks (a 512x512 frame's pixels, 4 MiB; zlib's state for each
/// EXR block) stay in the heap and are reused from frame to frame without
/// page faults: the heap keeps up to 16 MiB free at its top (twice the
/// threshold, as glibc's own adjustment would), where a fixed threshold
/// leaves the default 128 KiB and every frame's buffers were handed back to
/// the system and faulted in again (1755 faults a 512x512 frame; a fault
/// costs about 10 us in a virtual machine).
/// Call once at the start of main. Does nothing on other C libraries.
inline void unmapLargeBlocksWhenFreed() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, kMappedBlockBytes);
    mallopt(M_TRIM_THRESHOLD, 2 * kMappedBlockBytes);
#endif
}

} // namespace cutaway
