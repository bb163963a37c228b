#pragma once
// Private to io_gyro: the keys of the record sheet (`record:`) and of the
// limits (`tolerances:`) in campaign files, shared by the reader and the
// writer.

#include <array>
#include <type_traits>
#include <string>
#include <utility>

#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign.hpp"

namespace meridian::io::detail {

/// Each key with the member it fills (`R` is RecordSheet or const RecordSheet).
template <class R>
auto record_fields(R& r) {
  using Member = decltype(&r.observer);
  return std::array<std::pair<const char*, Member>, 9>{{{"observer", &r.observer},
                                                        {"booker", &r.booker},
                                                        {"computed_by", &r.computed_by},
                                                        {"checked_by", &r.checked_by},
                                                        {"date", &r.date},
                                                        {"weather", &r.weather},
                                                        {"temperature", &r.temperature},
                                                        {"remarks", &r.remarks},
                                                        {"language", &r.language}}};
}

/// A key of `tolerances:`, the member it fills and the file's unit in
/// radians or divisions (the file says arcsec or div).
template <class T>
struct ToleranceField {
  const char* key;
  T* member;
  double unit;
};

/// Each key of `tolerances:` (`T` is Tolerances or const Tolerances).
template <class T>
auto tolerance_fields(T& t) {
  using M = std::remove_reference_t<decltype((t.zero_position_div))>;  // const with a const T
  constexpr double arcsec = units::kArcsecond;
  return std::array<ToleranceField<M>, 10>{{{"determination_difference_arcsec", &t.determination_difference_rad, arcsec},
                                           {"instrument_constant_difference_arcsec",
                                            &t.instrument_constant_difference_rad, arcsec},
                                           {"instrument_constant_means_arcsec", &t.instrument_constant_means_rad, arcsec},
                                           {"orientation_difference_arcsec", &t.orientation_difference_rad, arcsec},
                                           {"orientation_mean_sigma_arcsec", &t.orientation_mean_sigma_rad, arcsec},
                                           {"zero_position_div", &t.zero_position_div, 1.0},
                                           {"zero_position_limit_div", &t.zero_position_limit_div, 1.0},
                                           {"known_azimuth_coordinates_arcsec", &t.known_azimuth_coordinates_rad, arcsec},
                                           {"instrument_constant_max_arcsec", &t.instrument_constant_max_rad, arcsec},
                                           {"line_coordinates_arcsec", &t.line_coordinates_rad, arcsec}}};
}

}  // namespace meridian::io::detail
