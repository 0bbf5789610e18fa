// libFuzzer's entry point. fuzz/CMakeLists.txt compiles this file once per
// fuzz target, with CUTAWAY_FUZZ_ENTRY naming the target's body in fuzz_entry.hpp.
#include "fuzz_entry.hpp"
#include "volume/read_budget.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Reading reserves a volume's declared size at once: keep it within the
    // fuzzer's 2 GiB memory limit, as --read-budget would on a small machine.
    static const bool budget = (cutaway::setReadBudget(std::uint64_t{256} << 20), true);
    (void)budget;
    cutaway::fuzz::CUTAWAY_FUZZ_ENTRY(data, size);
    return 0;
}
