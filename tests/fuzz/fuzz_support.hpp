#pragma once
// Shared by the libFuzzer harnesses: the input as a file (the readers take
// paths), and the rule every harness checks: a reader either returns a
// value or throws meridian::Error; anything else (std::bad_alloc,
// std::out_of_range, an exception of a library underneath) is a finding.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "meridian/core/error.hpp"

namespace meridian_fuzz {

/// A scratch directory of this process (libFuzzer's -fork/-jobs workers each
/// have their own), in memory where there is /dev/shm: on ext4, closing a
/// file that was truncated and rewritten flushes it to the disk, which made
/// each run cost milliseconds.
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    std::error_code ec;
    const char* env =
        std::getenv("MERIDIAN_FUZZ_SCRATCH");  // scripts/fuzz.sh's, removed when it ends
    const auto base = env && *env ? std::filesystem::path(env)
                      : std::filesystem::is_directory("/dev/shm", ec)
                          ? std::filesystem::path("/dev/shm")
                          : std::filesystem::temp_directory_path();
    const auto d = base / ("meridian-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {  // libFuzzer's own exits skip this; scripts/fuzz.sh cleans up after them
      std::error_code ignored;
      std::filesystem::remove_all(scratch(), ignored);
    });
    return d;
  }();
  return dir;
}

/// Writes `bytes` to scratch()/name and returns the path.
inline std::filesystem::path write(const std::string& name, std::string_view bytes) {
  const auto p = scratch() / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return p;
}

[[noreturn]] inline void finding(const char* what) {
  std::fprintf(stderr, "meridian-fuzz: %s\n", what);
  std::abort();
}

/// Runs `f`; meridian::Error is the expected answer to a bad input.
template <class F>
void expect_value_or_error(F&& f) {
  try {
    f();
  } catch (const meridian::Error&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meridian-fuzz: not a meridian::Error: %s\n", e.what());
    std::abort();
  } catch (...) {
    finding("an exception that is not a std::exception");
  }
}

/// A number a reader or an evaluation returned must be finite.
inline void check_finite(double v, const char* what) {
  if (!std::isfinite(v)) finding(what);
}

}  // namespace meridian_fuzz
