#pragma once
// The host memory reading a volume may take: a budget of its own, apart from
// the device's (--memory-budget). Every reader checks a volume's declared
// size against it before it allocates (detail::checkedByteCount), so a
// header that claims more than the machine can hold is refused at once,
// naming the file, instead of ending in "out of memory" minutes later.
#include <cstdint>
#include <optional>

namespace cutaway {

/// The budget by default: half the machine's physical memory (reading a
/// volume takes its declared size plus a 1 MiB buffer; docs/reliability.md).
std::uint64_t defaultReadBudget();

/// The budget in force: set by setReadBudget (`--read-budget`), else the default.
std::uint64_t readBudget();

/// Sets the budget for this process; nullopt restores the default.
void setReadBudget(std::optional<std::uint64_t> bytes);

} // namespace cutaway
