#include "gyro_runs.hpp"

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::cli {

ReducedFile reduce_file(const std::string& path, Progress* progress) {
  ReducedFile r{io::read_gyro_reduce_file(path), {}, {}};
  const io::GyroReduceFile& f = r.file;
  r.instrument = gyro::resolve_instrument(f.instrument, f.latitude_rad);
  for (std::size_t i = 0; i < f.determinations.size(); ++i) {
    report_progress(progress, i, f.determinations.size(), "determinations");
    try {
      r.results.push_back(gyro::reduce_determination(f.determinations[i], r.instrument.instrument, f.options));
    } catch (Error& e) {
      e.add_context("", std::nullopt, fmt::format("determinations[{}]", i));
      io::locate_error(e, f.file, f.lines);
      throw;
    }
  }
  return r;
}

gyro::CampaignResult process_campaign_file(const io::CampaignFile& f, Progress* progress) {
  try {
    return gyro::process_campaign(f.campaign, progress);
  } catch (Error& e) {
    io::locate_error(e, f.file, f.lines);
    throw;
  }
}

}  // namespace meridian::cli
