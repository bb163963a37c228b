#include "meridian/core/scratch_array.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace meridian {
namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;

// madvise(advice) on the whole `align`-aligned blocks inside [p, p + bytes), if any.
[[maybe_unused]] void advise_aligned_interior(void* p, std::size_t bytes, std::size_t align, int advice) noexcept {
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + align - 1) / align * align;
  const std::uintptr_t last = (begin + bytes) / align * align;
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, advice);
}
}  // namespace

void advise_huge_pages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_HUGEPAGE
  advise_aligned_interior(p, bytes, kHugePage, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

void populate_pages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_POPULATE_WRITE
  if (bytes >= (std::size_t{1} << 20)) advise_aligned_interior(p, bytes, 4096, MADV_POPULATE_WRITE);
#else
  (void)p;
  (void)bytes;
#endif
}

std::vector<double> large_zero_vector(std::size_t n) {
  std::vector<double> v;
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(double));
  v.resize(n);
  return v;
}

ScratchArray::ScratchArray(std::size_t n) : size_(n) {
  if (n == 0) return;
  if (n > SIZE_MAX / sizeof(double) - kHugePage) throw std::bad_alloc();
  std::size_t bytes = n * sizeof(double);
  void* p = nullptr;
  if (bytes >= kHugePage) {
    bytes = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    p = std::aligned_alloc(kHugePage, bytes);
    if (p != nullptr) advise_huge_pages(p, bytes);
  } else {
    p = std::malloc(bytes);
  }
  if (p == nullptr) throw std::bad_alloc();
  data_.reset(static_cast<double*>(p));
}

void ScratchArray::Free::operator()(double* p) const noexcept { std::free(p); }

}  // namespace meridian
