#pragma once
// How the process's allocator treats large blocks, for programs that hold volumes.
#include <cstddef>
#include <sys/resource.h>
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

/// The malloc arenas a process may have under an address-space limit.
inline constexpr int kArenasUnderAddressLimit = 2;

/// Under an address-space limit (RLIMIT_AS, `ulimit -v`), has glibc share
/// kArenasUnderAddressLimit malloc arenas among all threads. By default each
/// thread that allocates gets an arena of its own, up to eight per core,
/// each reserving 64 MiB of address space: lavapipe's rasterizer threads
/// made a tiny frame need 690 MiB of address space with 2 threads and
/// 1490 MiB with 16, against 310 and 590 with shared arenas (measured).
/// Without a limit nothing changes. Call once at the start of main, before
/// any thread starts. Does nothing on other C libraries.
inline void shareArenasUnderAddressLimit() {
#if defined(__GLIBC__)
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        mallopt(M_ARENA_MAX, kArenasUnderAddressLimit);
#endif
}

} // namespace cutaway
