#pragma once
// Private to io_dov (not installed): the names of the line file's matrix columns, shared by
// its reader (dov_files.cpp) and its writer (dov_writers.cpp).

#include <string>

#include <fmt/format.h>

namespace meridian::io::detail {

/// "lgu_23": element (i, j), 0-based, of the attitude matrix `prefix` (lgu or ins), 1-based in
/// the name.
inline std::string dov_element_column(const char* prefix, int i, int j) {
  return fmt::format("{}_{}{}", prefix, i + 1, j + 1);
}

}  // namespace meridian::io::detail
