#include "meridian/gravity/simd_kernel.hpp"

#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gravity {

std::string_view to_string(SimdKernel k) noexcept {
  switch (k) {
    case SimdKernel::Baseline: return "baseline";
    case SimdKernel::X86_64_V3: return "x86-64-v3";
    case SimdKernel::X86_64_V4: return "x86-64-v4";
    case SimdKernel::Auto: break;
  }
  return "auto";
}

SimdKernel parse_simd_kernel(std::string_view text, std::string_view field) {
  for (SimdKernel k : {SimdKernel::Auto, SimdKernel::Baseline, SimdKernel::X86_64_V3, SimdKernel::X86_64_V4})
    if (text == to_string(k)) return k;
  throw InputError(fmt::format("\"{}\" is not a summation kernel (auto, baseline, x86-64-v3, x86-64-v4)", text),
                   {"", {}, std::string(field)});
}

bool simd_kernel_supported(SimdKernel k) noexcept {
#if defined(__x86_64__) && !defined(MERIDIAN_NO_TARGET_CLONES)
  // Feature by feature (not "x86-64-v3", which clang 14 does not know): the instructions the
  // kernels' target attributes allow the compiler to use.
  __builtin_cpu_init();
  const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                  __builtin_cpu_supports("bmi2");
  switch (k) {
    case SimdKernel::X86_64_V3: return v3;
    case SimdKernel::X86_64_V4:
      return v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl");
    default: return true;
  }
#else
  return k == SimdKernel::Auto || k == SimdKernel::Baseline;
#endif
}

std::vector<SimdKernel> supported_simd_kernels() {
  std::vector<SimdKernel> out;
  for (SimdKernel k : {SimdKernel::Baseline, SimdKernel::X86_64_V3, SimdKernel::X86_64_V4})
    if (simd_kernel_supported(k)) out.push_back(k);
  return out;
}

SimdKernel resolve_simd_kernel(SimdKernel k) {
  std::string field = "simd_kernel";
  if (k == SimdKernel::Auto) {
    const char* env = std::getenv(kSimdKernelEnv);
    if (env == nullptr || *env == '\0') return supported_simd_kernels().back();
    field = kSimdKernelEnv;
    k = parse_simd_kernel(env, field);
    if (k == SimdKernel::Auto) return supported_simd_kernels().back();
  }
  if (!simd_kernel_supported(k))
    throw InputError(fmt::format("the summation kernel {} needs instructions this CPU (or this build) does not "
                                 "have; available: {}",
                                 to_string(k), [] {
                                   std::string s;
                                   for (SimdKernel c : supported_simd_kernels())
                                     s += (s.empty() ? "" : ", ") + std::string(to_string(c));
                                   return s;
                                 }()),
                     {"", {}, field});
  return k;
}

}  // namespace meridian::gravity
