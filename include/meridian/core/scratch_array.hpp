#pragma once
/// \file scratch_array.hpp
/// Large uninitialised arrays of doubles for the scratch space of numerics that stream over
/// millions of samples (wavelet transforms), allocated so that their first touch is cheap.
///
/// Why: the first write to fresh memory costs the kernel one page fault per 4 kB page; on a
/// virtual machine that is several µs each (measured 5.7 ms to zero-fill 8 MB of fresh
/// `std::vector<double>` on the 2-core KVM guest of docs/benchmarks.md, 0.7 ms with huge pages),
/// more than the arithmetic of a wavelet level. From 2 MB up a ScratchArray is 2 MB-aligned and
/// advised to the kernel as transparent huge pages (madvise MADV_HUGEPAGE; honoured when
/// /sys/kernel/mm/transparent_hugepage/enabled is "always" or "madvise", ignored otherwise), so
/// it faults in 2 MB at a time. Nothing is zero-filled.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace meridian {

/// Advise the kernel to back the whole 2 MB-aligned part of [p, p + bytes) with transparent
/// huge pages before it is first touched. Advice only: a failure (or a kernel without
/// transparent huge pages) changes nothing but speed. No effect on ranges under 2 MB.
void advise_huge_pages(void* p, std::size_t bytes) noexcept;

/// Ask the kernel to fault in every whole 4 kB page of [p, p + bytes) now, in one call
/// (madvise MADV_POPULATE_WRITE, Linux 5.14), instead of one page fault per page on first
/// touch: for memory that is about to be written entirely (a file read into it). Advice only:
/// a failure (an older kernel, no memory to spare) changes nothing but speed. No effect under
/// 1 MB.
void populate_pages(void* p, std::size_t bytes) noexcept;

/// A std::vector<double> of n zeros whose storage is advised huge pages (advise_huge_pages) before
/// the zero fill touches it — for results that leave the numerics as std::vector. Throws
/// std::bad_alloc.
std::vector<double> large_zero_vector(std::size_t n);

/// n uninitialised doubles (see the file comment). Move-only. Throws std::bad_alloc.
class ScratchArray {
 public:
  ScratchArray() = default;
  explicit ScratchArray(std::size_t n);
  double* data() noexcept { return data_.get(); }
  const double* data() const noexcept { return data_.get(); }
  std::size_t size() const noexcept { return size_; }
  std::span<double> span() noexcept { return {data_.get(), size_}; }

 private:
  struct Free {
    void operator()(double* p) const noexcept;
  };
  std::unique_ptr<double, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace meridian
