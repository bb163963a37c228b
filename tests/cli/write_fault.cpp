// Test-only LD_PRELOAD shim: every write to a file whose path contains
// $MERIDIAN_FAULT_PATH fails with ENOSPC, as on a full disk. statvfs is left
// alone, so the writers' own free-space checks pass and the failure comes where
// a disk that fills during the run puts it. Used by Cli.AFullDisk*.
#include <dlfcn.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

bool faulty(int fd) {
  const char* want = std::getenv("MERIDIAN_FAULT_PATH");
  if (!want || !*want) return false;
  char link[64], path[4096];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link, path, sizeof path - 1);
  if (n <= 0) return false;
  path[n] = '\0';
  return std::strstr(path, want) != nullptr;
}

template <class F>
F real(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

}  // namespace

extern "C" {

ssize_t write(int fd, const void* buf, size_t count) {
  static const auto next = real<ssize_t (*)(int, const void*, size_t)>("write");
  if (count > 0 && faulty(fd)) return errno = ENOSPC, -1;
  return next(fd, buf, count);
}

ssize_t pwrite(int fd, const void* buf, size_t count, off_t offset) {
  static const auto next = real<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite");
  if (count > 0 && faulty(fd)) return errno = ENOSPC, -1;
  return next(fd, buf, count, offset);
}

ssize_t pwrite64(int fd, const void* buf, size_t count, off_t offset) {
  static const auto next = real<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite64");
  if (count > 0 && faulty(fd)) return errno = ENOSPC, -1;
  return next(fd, buf, count, offset);
}

ssize_t writev(int fd, const struct iovec* iov, int iovcnt) {
  static const auto next = real<ssize_t (*)(int, const struct iovec*, int)>("writev");
  if (iovcnt > 0 && faulty(fd)) return errno = ENOSPC, -1;
  return next(fd, iov, iovcnt);
}

}  // extern "C"
