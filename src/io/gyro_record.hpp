#pragma once
// Private to io_gyro: the keys of the record sheet (`record:`) in campaign
// files, shared by the reader and the writer.

#include <array>
#include <string>
#include <utility>

#include "meridian/gyro/campaign.hpp"

namespace meridian::io::detail {

/// Each key with the member it fills (`R` is RecordSheet or const RecordSheet).
template <class R>
auto record_fields(R& r) {
  using Member = decltype(&r.observer);
  return std::array<std::pair<const char*, Member>, 8>{{{"observer", &r.observer},
                                                        {"booker", &r.booker},
                                                        {"computed_by", &r.computed_by},
                                                        {"checked_by", &r.checked_by},
                                                        {"date", &r.date},
                                                        {"weather", &r.weather},
                                                        {"temperature", &r.temperature},
                                                        {"remarks", &r.remarks}}};
}

}  // namespace meridian::io::detail
