#include "io/halves.hpp"

#include <cmath>
#include <cstring>

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#include <cpuid.h>
#include <immintrin.h>
#define CUTAWAY_F16C 1
#endif

namespace cutaway {

namespace {

constexpr float kHalfMax = 65504.0f; // the largest finite half

#ifdef CUTAWAY_F16C
// Compiled for F16C alone; called only where the CPU has it.
__attribute__((target("avx,f16c"))) void toHalvesF16c(const float* in, half* out,
                                                      std::size_t count) {
    const __m256 most = _mm256_set1_ps(kHalfMax);
    const __m256 least = _mm256_set1_ps(-kHalfMax);
    std::size_t i = 0;
    for (; i + 8 <= count; i += 8) {
        __m256 v = _mm256_loadu_ps(in + i);
        v = _mm256_and_ps(v, _mm256_cmp_ps(v, v, _CMP_ORD_Q)); // NaN -> +0
        v = _mm256_min_ps(_mm256_max_ps(v, least), most);
        const __m128i h = _mm256_cvtps_ph(v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
        std::memcpy(static_cast<void*>(out + i), &h, sizeof h); // half: a 16-bit value type
    }
    for (; i < count; ++i)
        out[i] = toHalf(in[i]);
}

// F16C from CPUID (clang's __builtin_cpu_supports does not know it); AVX
// through the builtin, which also asks whether the system saves its registers.
bool hasF16c() {
    static const bool has = [] {
        unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
        if (__get_cpuid(1, &eax, &ebx, &ecx, &edx) == 0) return false;
        return (ecx & bit_F16C) != 0 && __builtin_cpu_supports("avx");
    }();
    return has;
}
#endif

} // namespace

half toHalf(float value) {
    if (std::isnan(value)) return half(0.0f);
    if (value > kHalfMax) return half(kHalfMax);
    if (value < -kHalfMax) return half(-kHalfMax);
    return half(value);
}

void toHalves(const float* in, half* out, std::size_t count) {
#ifdef CUTAWAY_F16C
    if (hasF16c()) {
        toHalvesF16c(in, out, count);
        return;
    }
#endif
    for (std::size_t i = 0; i < count; ++i)
        out[i] = toHalf(in[i]);
}

} // namespace cutaway
