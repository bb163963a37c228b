#pragma once
// Shared plumbing of the meridian CLI: exit codes, error reporting and
// output. The CLI only parses, calls the library and formats.

#include <chrono>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "meridian/core/progress.hpp"

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

/// Write `text` to standard output and flush it; throws IoError ("cannot write to standard
/// output: No space left on device") when the write or the flush fails, so that a full disk
/// behind `> out.csv`, /dev/full or a closed descriptor exits 4, never 0 with a cut file.
/// A closed pipe ends the process by SIGPIPE first, as for any Unix filter. `flush` false:
/// buffered (a streamed CSV row by row); the error then shows at a later write or flush.
void write_standard_output(std::string_view text, bool flush = true);

/// Flush and close standard output at the end of a run (std::cout and C stdio share it);
/// returns false, with the message on stderr, when that fails: the caller exits kIoError.
bool close_standard_output();

/// One output of emit_all: `text` to `path` ("-": standard output; empty: not written).
struct Output {
  const std::string& path;
  const std::string& text;
};
/// Several outputs of one run, all or none: every file's temporary is created and written
/// before any is renamed into place, so a report in a missing directory no longer leaves the
/// text output written (cli.md: on an error nothing is written); standard output last.
void emit_all(std::initializer_list<Output> outputs);
/// "-", the path of standard output in emit_all.
inline const std::string kStandardOutput = "-";

/// The outputs of most workflow commands: the summary `text` (text or JSON) to `output` (empty
/// or "-": standard output) and, when `report_path` is not empty, the HTML report `html()` (built
/// only then), all or none (emit_all). Call it after everything is computed.
void emit_with_report(const std::string& output, const std::string& text, const std::string& report_path,
                      const std::function<std::string()>& html);

/// When `report_path` is not empty and this build has no HTML reports, throw
/// an Error saying how to enable them, before any work is done.
void require_html_reports_for(const std::string& report_path);

/// True when paths a and b name the same file, compared as absolute, normalised paths (neither
/// need exist yet: two outputs about to be written).
bool same_path(const std::string& a, const std::string& b);

/// An output file of a command, for check_output_paths: its path (empty: none; "-" standard output,
/// which two outputs cannot share either), the option
/// that names it ("--report") and what it holds ("report").
struct OutputPath {
  const std::string& path;
  const char* option;
  const char* what;
};
/// Before any work: refuse two outputs on one file ("-o and --report name the same file X") and an
/// output that would replace one of `inputs` ("the report would overwrite the input X", field =
/// the option), paths compared normalised and, for files that exist, as the same file.
void check_output_paths(std::initializer_list<OutputPath> outputs, const std::vector<std::string>& inputs);

/// An angle option as typed (DMS or decimal degrees, core/dms.hpp) in radians; a parse error
/// names the option (`name`, e.g. "--latitude").
double angle_option(const std::string& text, const char* name);

/// A progress bar on stderr for runs longer than a second: drawn only when
/// stderr is a terminal and not `quiet`, at most ten times a second, and
/// cleared by finish(). MERIDIAN_PROGRESS_DELAY_S overrides the one-second
/// delay (tests use 0).
class TerminalProgress : public Progress {
 public:
  explicit TerminalProgress(bool quiet);
  ~TerminalProgress() override;
  void update(std::size_t done, std::size_t total, std::string_view what) override;
  void finish() override;

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  bool drawn_ = false;
  double delay_s_ = 1.0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_draw_{};
};

}  // namespace meridian::cli
