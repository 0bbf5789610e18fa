// libFuzzer's entry point. fuzz/CMakeLists.txt compiles this file once per
// fuzz target, with CUTAWAY_FUZZ_ENTRY naming the target's body in fuzz_entry.hpp.
#include "fuzz_entry.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    cutaway::fuzz::CUTAWAY_FUZZ_ENTRY(data, size);
    return 0;
}
