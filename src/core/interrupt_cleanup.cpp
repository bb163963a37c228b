#include "meridian/core/interrupt_cleanup.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace meridian {

namespace {

// A slot is free (0), being filled by its new owner (1), or holds a path the handler may
// unlink (2). Only the owner empties its slot; the handler only reads.
struct Slot {
  std::atomic<int> state{0};
  char path[kMaxTemporaryPath + 1];
};

Slot g_slots[kMaxTemporaryFiles];  // the registry (see the header: a signal handler's state)

static_assert(std::atomic<int>::is_always_lock_free, "the handler needs lock-free atomics");

extern "C" void remove_temporary_files_and_die(int sig) {
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == 2) ::unlink(s.path);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

}  // namespace

TemporaryFileGuard::TemporaryFileGuard(const std::string& path) { reset(path); }

TemporaryFileGuard::TemporaryFileGuard(TemporaryFileGuard&& other) noexcept : slot_(other.slot_) {
  other.slot_ = -1;
}

TemporaryFileGuard& TemporaryFileGuard::operator=(TemporaryFileGuard&& other) noexcept {
  if (this != &other) {
    release();
    slot_ = other.slot_;
    other.slot_ = -1;
  }
  return *this;
}

void TemporaryFileGuard::reset(const std::string& relative) {
  release();
  // Absolute: the handler must not depend on the working directory at the time.
  std::error_code ec;
  const std::string path = std::filesystem::absolute(relative, ec).string();
  if (ec || path.empty() || path.size() > kMaxTemporaryPath) return;
  for (std::size_t i = 0; i < kMaxTemporaryFiles; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].state.store(2, std::memory_order_release);
    slot_ = static_cast<int>(i);
    return;
  }
}

void TemporaryFileGuard::release() noexcept {
  if (slot_ < 0) return;
  g_slots[slot_].state.store(0, std::memory_order_release);
  slot_ = -1;
}

void install_interrupt_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = remove_temporary_files_and_die;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  // A signal ignored on entry stays ignored: nohup's SIGHUP, the SIGINT of a background job
  // started by a shell without job control.
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &sa, nullptr);
  }
}

std::size_t registered_temporary_files() noexcept {
  std::size_t n = 0;
  for (const Slot& s : g_slots) n += s.state.load(std::memory_order_acquire) == 2 ? 1 : 0;
  return n;
}

}  // namespace meridian
