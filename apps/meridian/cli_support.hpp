#pragma once
// Shared plumbing of the meridian CLI: exit codes, error reporting and
// output. The CLI only parses, calls the library and formats.

#include <functional>
#include <string>

namespace meridian::cli {

/// Exit codes (documented in docs/cli.md).
enum ExitCode : int {
  kOk = 0,
  kInputError = 1,      ///< bad input file or argument value
  kUsage = 2,           ///< bad command line
  kNumericalError = 3,  ///< singular system, no convergence, …
  kIoError = 4,         ///< cannot read or write a file
  kInternalError = 5,
};

/// Run `body`, turning exceptions into a one-line "meridian: error: …" on
/// stderr and the matching exit code.
int guarded(const std::function<int()>& body);

/// Write `text` to `path` atomically, or to stdout when path is empty or "-".
void emit(const std::string& path, const std::string& text);

}  // namespace meridian::cli
