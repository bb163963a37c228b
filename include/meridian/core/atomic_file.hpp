#pragma once
/// \file atomic_file.hpp
/// Atomic output: write to a temporary file beside the target, flush it to
/// disk, then rename over the target. An interrupted run never leaves a
/// half-written result; on failure the target is untouched.

#include <filesystem>
#include <string_view>

namespace meridian {

/// Write `content` to `path` atomically. Throws IoError naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace meridian
