#include "meridian/gyro/instrument_spec.hpp"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {

ResolvedInstrument resolve_instrument(const InstrumentSpec& spec, double station_lat_rad) {
  ResolvedInstrument out;
  Instrument& inst = out.instrument;
  if (!(spec.scale_value_rad > 0.0) || !std::isfinite(spec.scale_value_rad))
    throw InputError("scale value must be a positive number", {"", std::nullopt, "scale_value_arcsec"});
  check_latitude(station_lat_rad, spec.latitude_limit_rad);
  inst.scale_value_rad = spec.scale_value_rad;
  inst.sigma_scale_value_rad = spec.sigma_scale_value_rad;
  inst.sigma_time_s = spec.sigma_time_s;
  inst.sigma_reading_div = spec.sigma_reading_div;

  const bool has_periods = spec.nontracking_period_s || spec.free_period_s;
  Uncertain lambda0;
  if (spec.torsion_ratio) {
    if (has_periods)
      throw InputError("give either torsion_ratio or periods, not both", {"", std::nullopt, "torsion_ratio"});
    lambda0 = *spec.torsion_ratio;
  } else if (has_periods) {
    if (!spec.tracking_period_s)
      throw InputError("the tracking period T_A is needed to compute lambda from periods",
                       {"", std::nullopt, "periods.tracking_s"});
    if (spec.nontracking_period_s && spec.free_period_s)
      throw InputError("give the non-tracking period or the free period, not both",
                       {"", std::nullopt, "periods"});
    if (spec.nontracking_period_s) {
      lambda0 = torsion_ratio_from_nontracking_period(*spec.tracking_period_s, *spec.nontracking_period_s);
      out.notes.push_back(fmt::format("lambda = (T_A/T_B)^2 - 1 = {:.5f} from periods", lambda0.value));
    } else {
      lambda0 = torsion_ratio_from_free_period(*spec.tracking_period_s, *spec.free_period_s);
      out.notes.push_back(fmt::format("lambda = (T_A/T_F)^2 = {:.5f} from periods", lambda0.value));
    }
  } else {
    throw InputError("the torsion ratio lambda is missing: give torsion_ratio or periods",
                     {"", std::nullopt, "torsion_ratio"});
  }
  if (!(lambda0.value >= 0.0) || !std::isfinite(lambda0.value))
    throw InputError(fmt::format("torsion ratio must be >= 0 (got {})", lambda0.value),
                     {"", std::nullopt, "torsion_ratio"});

  // λ and a calibrated c hold at constants_latitude (or at the station):
  // rescale them; say so only where the printed value changes.
  inst.torsion_ratio = lambda0;
  inst.transit_factor_rad_per_div_s = spec.transit_factor_rad_per_div_s;
  if (spec.constants_latitude_rad) {
    const double lat0 = *spec.constants_latitude_rad;
    inst.torsion_ratio = rescale_torsion_ratio(lambda0, lat0, station_lat_rad, spec.latitude_limit_rad);
    const auto shown = [](double v, int decimals) { return fmt::format("{:.{}f}", v, decimals); };
    if (shown(lambda0.value, 5) != shown(inst.torsion_ratio.value, 5))
      out.notes.push_back(fmt::format("lambda rescaled from {:.5f} at {:.4f} deg to {:.5f} at {:.4f} deg",
                                      lambda0.value, lat0 / units::kDegree, inst.torsion_ratio.value,
                                      station_lat_rad / units::kDegree));
    if (spec.transit_factor_rad_per_div_s) {
      const Uncertain c0 = *spec.transit_factor_rad_per_div_s;
      inst.transit_factor_rad_per_div_s =
          rescale_transit_factor(c0, lambda0.value, lat0, station_lat_rad, spec.latitude_limit_rad);
      const double c = inst.transit_factor_rad_per_div_s->value;
      if (shown(c0.value / units::kArcsecond, 4) != shown(c / units::kArcsecond, 4))
        out.notes.push_back(fmt::format(
            "calibrated transit factor c rescaled from {:.4f} at {:.4f} deg to {:.4f} \"/(div s) at {:.4f} deg",
            c0.value / units::kArcsecond, lat0 / units::kDegree, c / units::kArcsecond,
            station_lat_rad / units::kDegree));
    }
  }
  return out;
}

std::optional<double> accuracy_class_from_name(const std::string& name) {
  std::string up;
  for (char c : name) up += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (up.find("GAK1") != std::string::npos || up.find("GAK 1") != std::string::npos) return 15.0;
  for (std::size_t p = up.find("JT"); p != std::string::npos; p = up.find("JT", p + 1)) {
    // Not inside a longer word ("BJT15" is not a JT15).
    if (p > 0 && std::isalnum(static_cast<unsigned char>(up[p - 1]))) continue;
    std::size_t q = p + 2;
    if (q < up.size() && (up[q] == '-' || up[q] == ' ')) ++q;
    std::size_t digits = 0;
    while (q + digits < up.size() && std::isdigit(static_cast<unsigned char>(up[q + digits]))) ++digits;
    if (digits == 0 || digits > 2) continue;
    if (q + digits < up.size() && std::isalnum(static_cast<unsigned char>(up[q + digits]))) continue;
    return std::stod(up.substr(q, digits));
  }
  return std::nullopt;
}

}  // namespace meridian::gyro
