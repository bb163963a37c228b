#pragma once
// Test helpers of the dov tests.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "meridian/core/units.hpp"

namespace meridian_test {

inline constexpr double kAs = meridian::units::kArcsecond;  ///< radians per arc-second

/// A fresh directory meridian_test_<name>_<pid> under the system's temporary directory.
inline std::filesystem::path temp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() /
                 ("meridian_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

/// Write `bytes` to `p` as they are.
inline void write(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream f(p, std::ios::binary);
  f << bytes;
}

}  // namespace meridian_test
