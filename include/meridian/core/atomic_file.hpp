#pragma once
/// \file atomic_file.hpp
/// Atomic output: write to a temporary file beside the target, flush it to
/// disk, then rename over the target. An interrupted run never leaves a
/// half-written result; on failure the target is untouched.

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "meridian/core/interrupt_cleanup.hpp"

namespace meridian {

/// Write `content` to `path` atomically. Throws IoError naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Streaming atomic output for long runs: chunks go to a temporary file
/// beside `path`; commit() flushes it to disk and renames it into place. If
/// the writer is destroyed without commit() (an error, an interrupted run)
/// the temporary file is removed and `path` is untouched; on SIGINT/SIGTERM too, where the CLI
/// installed install_interrupt_cleanup().
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::filesystem::path path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(std::string_view chunk);
  /// Overwrite bytes already written, at `offset` from the start of the file (a header whose
  /// count is known only at the end). Throws IoError when offset + size is beyond what was
  /// written, or the write fails.
  void write_at(std::uint64_t offset, std::string_view bytes);
  void commit();

 private:
  std::filesystem::path path_;
  std::string tmp_;
  int fd_ = -1;
  std::uint64_t written_ = 0;  // bytes written by write()
  TemporaryFileGuard guard_;   // tmp_ removed on SIGINT/SIGTERM too (interrupt_cleanup.hpp)
};

}  // namespace meridian
