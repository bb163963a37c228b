#include "meridian/gyro/reduce.hpp"

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gyro {

ReduceResult process(const ReduceInput& in, Progress* progress) {
  ReduceResult r;
  r.input = in;
  try {
    r.instrument = resolve_instrument(in.instrument, in.latitude_rad);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "instrument");
    throw;
  }
  for (std::size_t i = 0; i < in.determinations.size(); ++i) {
    report_progress(progress, i, in.determinations.size(), "determinations");
    try {
      r.determinations.push_back(reduce_determination(in.determinations[i], r.instrument.instrument, in.options));
    } catch (Error& e) {
      e.add_context("", std::nullopt, fmt::format("determinations[{}]", i));
      throw;
    }
  }
  return r;
}

}  // namespace meridian::gyro
