#pragma once
/// \file simd_kernel.hpp
/// Which instruction set the spherical-harmonic summation kernel of GravityField uses.
///
/// The kernel is compiled three times and chosen at run time, so one binary runs at full speed
/// on every x86-64 CPU:
///
/// | kernel | instructions | points per vector |
/// | --- | --- | --- |
/// | `baseline` | x86-64 (SSE2), any CPU | 2 (one 128-bit vector) |
/// | `x86-64-v3` | AVX2 + FMA (Haswell, Zen 1 and later) | 4 (one 256-bit vector) |
/// | `x86-64-v4` | AVX-512 F/CD/BW/DQ/VL (Skylake-SP, Zen 4 and later) | 8 (one 512-bit vector) |
///
/// One pass over the coefficients evaluates up to 16 points (or the column sums of 16 grid
/// parallels) as 16 ÷ width groups of one vector each, each group in the kernel's native
/// width: the recursion of the deflection (gradient) kernel keeps 16 vectors live, which fits
/// the 16 AVX2 registers only at 256 bits (8-point vectors split into 2 × 256-bit halves spill
/// on AVX2: several times slower, issue 14). All kernels compute the same sums in the same
/// order per point; they differ only by the rounding of fused multiply-adds (baseline has none),
/// about 1e-15 relative (tests/gravity/test_simd_kernels.cpp checks 1e-12).
///
/// On other architectures, and in builds with MERIDIAN_NO_TARGET_CLONES, only `baseline` exists
/// (the compiler's own vectorisation of the portable code).
#include <string_view>
#include <vector>

namespace meridian::gravity {

enum class SimdKernel {
  Auto,      ///< MERIDIAN_SIMD_KERNEL from the environment if set, else the widest supported
  Baseline,  ///< "baseline"
  X86_64_V3, ///< "x86-64-v3"
  X86_64_V4, ///< "x86-64-v4"
};

/// The environment variable that `SimdKernel::Auto` consults (values as to_string; "auto" or
/// empty = the widest supported): for benchmarks and for checking a result on another path.
inline constexpr const char* kSimdKernelEnv = "MERIDIAN_SIMD_KERNEL";

/// "auto", "baseline", "x86-64-v3" or "x86-64-v4".
std::string_view to_string(SimdKernel k) noexcept;
/// The inverse of to_string; throws InputError (field `field`) for any other text.
SimdKernel parse_simd_kernel(std::string_view text, std::string_view field = "simd_kernel");
/// True when this CPU (and this build) can run `k`; Auto and Baseline always.
bool simd_kernel_supported(SimdKernel k) noexcept;
/// The concrete kernels this CPU can run, baseline first, widest last.
std::vector<SimdKernel> supported_simd_kernels();
/// The concrete kernel `k` stands for: Auto → the environment's choice or the widest supported.
/// Throws InputError when `k`, or the kernel the environment names, is not supported here
/// (field "simd_kernel" or "MERIDIAN_SIMD_KERNEL").
SimdKernel resolve_simd_kernel(SimdKernel k);

}  // namespace meridian::gravity
