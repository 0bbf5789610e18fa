#include "volume/read_budget.hpp"

#include <atomic>
#include <unistd.h>

namespace cutaway {
namespace {

std::atomic<std::uint64_t> g_budget{0}; // 0: the default

} // namespace

std::uint64_t defaultReadBudget() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page <= 0) return std::uint64_t{4} << 30;
    return std::uint64_t(pages) * std::uint64_t(page) / 2;
}

std::uint64_t readBudget() {
    const std::uint64_t set = g_budget.load();
    return set ? set : defaultReadBudget();
}

void setReadBudget(std::optional<std::uint64_t> bytes) {
    g_budget = bytes.value_or(0);
}

} // namespace cutaway
