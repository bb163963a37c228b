#include "cli_support.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/report/html.hpp"

namespace meridian::cli {

int guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << "meridian: error: " << e.what() << "\n";
    return kInputError;
  } catch (const NumericalError& e) {
    std::cerr << "meridian: numerical failure: " << e.what() << "\n";
    return kNumericalError;
  } catch (const IoError& e) {
    std::cerr << "meridian: I/O error: " << e.what() << "\n";
    return kIoError;
  } catch (const Error& e) {
    std::cerr << "meridian: error: " << e.what() << "\n";
    return kInputError;
  } catch (const std::exception& e) {
    std::cerr << "meridian: internal error: " << e.what() << "\n";
    return kInternalError;
  }
}

void require_html_reports_for(const std::string& report_path) {
  if (!report_path.empty() && !report::html_reports_available())
    throw Error(report::html_reports_unavailable_message(), {"", std::nullopt, "--report"});
}

void write_standard_output(std::string_view text, bool flush) {
  errno = 0;
  // (fwrite of an empty view's null data is undefined: UBSan found it on the final flush)
  const std::size_t n = text.empty() ? 0 : std::fwrite(text.data(), 1, text.size(), stdout);
  if (n != text.size() || (flush && std::fflush(stdout) != 0) || std::ferror(stdout)) {
    const int err = errno;
    throw IoError(fmt::format("cannot write: {} ({} of {} bytes of this block written)",
                              err ? std::strerror(err) : "write failed", n, text.size()),
                  {"", std::nullopt, "standard output"});
  }
}

bool close_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  const int err = errno;
  const bool close_failed = std::fclose(stdout) != 0;
  if (failed || close_failed) {
    // The same words as a failed write_standard_output reported through guarded().
    std::fprintf(stderr, "meridian: I/O error: standard output: cannot write: %s\n",
                 err ? std::strerror(err) : close_failed ? std::strerror(errno) : "the write failed (a full disk or a closed descriptor?)");
    return false;
  }
  return true;
}

void emit(const std::string& path, const std::string& text) {
  if (path.empty() || path == "-") {
    write_standard_output(text);
    return;
  }
  write_file_atomically(path, text);
}

void emit_all(std::initializer_list<Output> outputs) {
  std::vector<std::unique_ptr<AtomicFileWriter>> files;
  for (const Output& o : outputs)
    if (!o.path.empty() && o.path != "-") {
      files.push_back(std::make_unique<AtomicFileWriter>(o.path));
      files.back()->write(o.text);
    }
  for (auto& f : files) f->commit();
  for (const Output& o : outputs)
    if (o.path == "-") emit("", o.text);
}

void check_output_paths(std::initializer_list<OutputPath> outputs, const std::vector<std::string>& inputs) {
  for (auto o = outputs.begin(); o != outputs.end(); ++o) {
    if (o->path.empty()) continue;
    for (auto later = std::next(o); later != outputs.end(); ++later)
      if (!later->path.empty() && same_path(o->path, later->path))
        throw InputError(fmt::format("{} and {} name the same file {}", o->option, later->option, o->path));
    for (const std::string& in : inputs) {
      std::error_code ec;
      if (!in.empty() && (same_path(o->path, in) || std::filesystem::equivalent(o->path, in, ec)))
        throw InputError(fmt::format("the {} would overwrite the input {}", o->what, in), {"", std::nullopt, o->option});
    }
  }
}

void emit_with_report(const std::string& output, const std::string& text, const std::string& report_path,
                      const std::function<std::string()>& html) {
  if (report_path.empty()) return emit(output, text);
  const std::string page = html();
  emit_all({{output.empty() ? kStandardOutput : output, text}, {report_path, page}});
}

TerminalProgress::TerminalProgress(bool quiet) : enabled_(!quiet && ::isatty(STDERR_FILENO) == 1) {
  if (const char* d = std::getenv("MERIDIAN_PROGRESS_DELAY_S")) delay_s_ = std::atof(d);
}

TerminalProgress::~TerminalProgress() { finish(); }

void TerminalProgress::update(std::size_t done, std::size_t total, std::string_view what) {
  if (!enabled_) return;
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < delay_s_) return;
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100) && done != total) return;
  last_draw_ = now;
  std::string line;
  if (total > 0) {
    const double f = static_cast<double>(done) / static_cast<double>(total);
    const int width = 30;
    const int fill = static_cast<int>(f * width);
    const double eta = f > 0 ? elapsed * (1.0 - f) / f : 0.0;
    line = fmt::format("\r{} [{}{}] {:3.0f}% {}/{}  ETA {:.0f} s ", what, std::string(static_cast<std::size_t>(fill), '#'),
                       std::string(static_cast<std::size_t>(width - fill), '.'), 100.0 * f, done, total, eta);
  } else {
    line = fmt::format("\r{} {} ", what, done);
  }
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
  drawn_ = true;
}

void TerminalProgress::finish() {
  if (!drawn_) return;
  std::fputs("\r\033[K", stderr);  // clear the bar's line
  std::fflush(stderr);
  drawn_ = false;
}

bool same_path(const std::string& a, const std::string& b) {
  return std::filesystem::absolute(a).lexically_normal() == std::filesystem::absolute(b).lexically_normal();
}

double angle_option(const std::string& text, const char* name) {
  try {
    return parse_angle(text).rad();
  } catch (Error& e) {
    e.add_context("", std::nullopt, name);
    throw;
  }
}

}  // namespace meridian::cli
