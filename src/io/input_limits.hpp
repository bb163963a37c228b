#pragma once
// Private helpers of every reader (io, io_gravity, io_nav, io_maglev, …): the longest text line
// a reader accepts, a bounded getline, and the check that a path names something a reader can
// read (a regular file or a FIFO; not a directory or a device). Inline, in one header, so that
// the readers, built as unity batches, share them (docs/reliability.md, "Limits").

#include <sys/stat.h>

#include <cstddef>
#include <filesystem>
#include <istream>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::io::detail {

/// The longest line a text reader accepts: 1 MiB (no field book, model header, CSV record or
/// NMEA log has lines near it; a file without line ends, or /dev/zero, is not read to the end
/// of memory).
inline constexpr std::size_t kMaxTextLineBytes = std::size_t{1} << 20;

/// The error for line `line` (1-based) beyond kMaxTextLineBytes.
inline ParseError line_too_long(const std::string& source, int line) {
  return ParseError(fmt::format("line {} is longer than 1 MiB: not a text file?", line), {source, line, ""});
}

/// std::getline with a bound: one line without its '\n' into `out`; false at the end of the
/// input (or when the stream has failed: check bad()). Throws line_too_long(source, line) when
/// the line has more than kMaxTextLineBytes bytes before its line end (LF, or CR LF: the CR is
/// not counted), having read at most 16 KiB more than that.
inline bool getline_bounded(std::istream& in, std::string& out, const std::string& source, int line) {
  out.clear();
  char buf[16384];
  bool any = false;
  for (;;) {
    in.getline(buf, sizeof buf);
    const auto got = static_cast<std::size_t>(in.gcount());
    if (in.bad()) return false;
    if (!in.fail()) {  // a line end was extracted (counted in gcount), or the input ended after text
      out.append(buf, in.eof() ? got : got - 1);
      const bool cr = !out.empty() && out.back() == '\r';
      if (out.size() - (cr ? 1 : 0) > kMaxTextLineBytes) throw line_too_long(source, line);
      return true;
    }
    if (got == sizeof buf - 1 && !in.eof()) {  // the buffer filled before a line end
      out.append(buf, got);
      any = true;
      if (out.size() > kMaxTextLineBytes + 1) throw line_too_long(source, line);  // + 1: a CR may follow
      in.clear();
      continue;
    }
    return any;  // nothing more: the line (if any) ended with the input
  }
}

/// Throws IoError naming `path` when it exists and is not a file a reader can read: a
/// directory, a character or block device (/dev/zero), a socket. Regular files and FIFOs
/// (`<(command)`) pass, and so does /dev/stdin (and /dev/fd/0, /proc/self/fd/0) whatever it is.
/// A path that does not exist passes: opening it then fails with the reader's own message.
inline void check_readable_path(const std::filesystem::path& path) {
  const std::string p = path.string();
  if (p == "/dev/stdin" || p == "/dev/fd/0" || p == "/proc/self/fd/0") return;
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return;
  if (S_ISREG(st.st_mode) || S_ISFIFO(st.st_mode)) return;
  const char* kind = S_ISDIR(st.st_mode)   ? "a directory"
                     : S_ISCHR(st.st_mode) ? "a character device"
                     : S_ISBLK(st.st_mode) ? "a block device"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                                            : "a special file";
  throw IoError(fmt::format("is {}, not a file that can be read", kind), {p, {}, ""});
}

}  // namespace meridian::io::detail
