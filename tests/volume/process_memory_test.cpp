// The allocator settings of a program that holds volumes: large blocks go back
// to the system when freed, a frame's buffers stay for the next frame.
#include "core/process_memory.hpp"

#include <cstdlib>
#include <cstring>
#include <gtest/gtest.h>
#include <sys/resource.h>

namespace cutaway::test {

// glibc only; sanitizers replace its allocator.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
namespace {

long minorFaults() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}

// Page faults taken by allocating `bytes`, writing every byte and freeing it.
long faultsOfABlock(std::size_t bytes) {
    const long before = minorFaults();
    void* block = std::malloc(bytes);
    std::memset(block, 1, bytes);
    // The block escapes, so the compiler cannot drop the pair of calls.
    asm volatile("" : : "r"(block) : "memory");
    std::free(block);
    return minorFaults() - before;
}

} // namespace

TEST(ProcessMemory, AFramesBufferIsReusedAndAVolumeIsHandedBack) {
    unmapLargeBlocksWhenFreed();
    constexpr std::size_t kFrame = 4 << 20; // a 512x512 frame of RGBA floats
    constexpr std::size_t kVolume = 64 << 20;
    constexpr long kPages = kFrame / 4096;
    faultsOfABlock(kFrame); // the heap grows once
    // Again: the heap kept the block (without the trim threshold it was
    // handed back and every page faulted again).
    EXPECT_LT(faultsOfABlock(kFrame), kPages / 8);
    // A volume is mapped on its own and unmapped when freed: its pages fault
    // in every time.
    EXPECT_GE(faultsOfABlock(kVolume), kVolume / 4096 / 2);
    EXPECT_GE(faultsOfABlock(kVolume), kVolume / 4096 / 2);
}
#endif

} // namespace cutaway::test
