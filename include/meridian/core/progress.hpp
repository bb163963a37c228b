#pragma once
/// \file progress.hpp
/// Progress reporting for long runs. Library code that loops over many
/// items accepts an optional `Progress*` and calls update(); it never draws
/// anything itself. The CLI supplies a terminal progress bar (stderr, only
/// on a TTY, silent with --quiet).

#include <cstddef>
#include <string_view>

namespace meridian {

/// Receives progress of a long computation. Implementations must be cheap
/// to call often (throttle drawing themselves).
class Progress {
 public:
  virtual ~Progress() = default;
  /// `done` of `total` items finished (total 0 = unknown); `what` names the
  /// phase ("simulating", "points").
  virtual void update(std::size_t done, std::size_t total, std::string_view what) = 0;
  /// The run is over (success or failure): clear any bar.
  virtual void finish() = 0;
};

/// Call p->update when p is not null.
inline void report_progress(Progress* p, std::size_t done, std::size_t total, std::string_view what) {
  if (p) p->update(done, total, what);
}

}  // namespace meridian
