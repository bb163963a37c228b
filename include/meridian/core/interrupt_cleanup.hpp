#pragma once
/// \file interrupt_cleanup.hpp
/// Temporary files removed when the process is interrupted (SIGINT, SIGTERM,
/// SIGHUP). An atomic writer's temporary file goes with its destructor on any
/// error; a signal runs no destructor, and Ctrl-C left `.profile.csv.tmp.*`
/// files of 10-68 MB behind (issue 35). Writers register their temporary
/// paths here for as long as they exist; the CLI installs the handler, which
/// unlinks every registered path and then dies of the same signal (exit status
/// 130 for SIGINT, 143 for SIGTERM in a shell).
///
/// The registry is process-wide state, the one kind a signal handler needs:
/// a fixed table of kMaxTemporaryFiles slots (lock-free atomics and unlink(2)
/// only: async-signal-safe). A path that does not fit (a full table, a path
/// longer than kMaxTemporaryPath bytes) is not registered: the file is then
/// still removed on errors, only not on a signal. Libraries never install the
/// handler (the Python package leaves signals to Python).

#include <cstddef>
#include <string>

namespace meridian {

/// Slots of the registry, and the longest path (bytes, without the NUL) it holds.
inline constexpr std::size_t kMaxTemporaryFiles = 64;
inline constexpr std::size_t kMaxTemporaryPath = 4095;

/// Registers `path` for removal on an interrupt while the guard lives; release() (after the
/// file was renamed into place or removed) or the destructor takes it out. Not copyable.
class TemporaryFileGuard {
 public:
  TemporaryFileGuard() = default;
  explicit TemporaryFileGuard(const std::string& path);
  ~TemporaryFileGuard() { release(); }
  TemporaryFileGuard(const TemporaryFileGuard&) = delete;
  TemporaryFileGuard& operator=(const TemporaryFileGuard&) = delete;
  TemporaryFileGuard(TemporaryFileGuard&& other) noexcept;
  TemporaryFileGuard& operator=(TemporaryFileGuard&& other) noexcept;

  /// Register `path` (releasing any earlier one).
  void reset(const std::string& path);
  /// The file is no longer this process's to remove.
  void release() noexcept;
  /// Whether a slot holds the path (false when the table was full or the path too long).
  bool registered() const noexcept { return slot_ >= 0; }

 private:
  int slot_ = -1;
};

/// Install handlers for SIGINT, SIGTERM and SIGHUP that unlink every registered temporary
/// file, then re-raise the signal with its default action. A signal ignored on entry (nohup's
/// SIGHUP) is left ignored. Call once, from main().
void install_interrupt_cleanup();

/// How many paths are registered now (for tests).
std::size_t registered_temporary_files() noexcept;

}  // namespace meridian
