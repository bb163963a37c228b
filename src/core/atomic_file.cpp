#include "meridian/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const char* what, int err) {
  throw IoError(fmt::format("{}: {}", what, std::strerror(err)), {path.string(), std::nullopt, {}});
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::filesystem::path path) : path_(std::move(path)) {
  namespace fs = std::filesystem;
  const fs::path dir = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
  tmp_ = (dir / ("." + path_.filename().string() + ".tmp.XXXXXX")).string();
  fd_ = ::mkstemp(tmp_.data());
  if (fd_ < 0)
    throw IoError(fmt::format("cannot create a temporary file in {}: {}", dir.string(), std::strerror(errno)),
                  {path_.string(), std::nullopt, {}});
  guard_.reset(tmp_);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(tmp_.c_str());
  }
}

namespace {

// All of `bytes` to fd: at the file position (write), or at `offset` (pwrite) when given.
void write_fully(int fd, const std::filesystem::path& path, std::string_view bytes,
                 std::optional<off_t> offset) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = offset ? ::pwrite(fd, p, left, *offset) : ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, "cannot write", errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
    if (offset) *offset += n;
  }
}

}  // namespace

void AtomicFileWriter::write(std::string_view chunk) {
  if (fd_ < 0) throw IoError("write after commit", {path_.string(), std::nullopt, {}});
  write_fully(fd_, path_, chunk, std::nullopt);
  written_ += chunk.size();
}

void AtomicFileWriter::write_at(std::uint64_t offset, std::string_view bytes) {
  if (fd_ < 0) throw IoError("write after commit", {path_.string(), std::nullopt, {}});
  if (offset > written_ || bytes.size() > written_ - offset)
    throw IoError(fmt::format("write_at({}, {} bytes) beyond the {} bytes written", offset,
                              bytes.size(), written_),
                  {path_.string(), std::nullopt, {}});
  write_fully(fd_, path_, bytes, static_cast<off_t>(offset));
}

void AtomicFileWriter::commit() {
  if (fd_ < 0) throw IoError("committed twice", {path_.string(), std::nullopt, {}});
  if (::fsync(fd_) != 0) fail(path_, "cannot flush to disk", errno);
  // mkstemp creates 0600; give the result ordinary permissions (umask applies).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd_, static_cast<mode_t>(0666 & ~mask));
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    fail(path_, "cannot close", err);
  }
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    fail(path_, "cannot rename the temporary file into place", err);
  }
  guard_.release();
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFileWriter w(path);
  w.write(content);
  w.commit();
}

}  // namespace meridian
