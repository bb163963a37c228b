#pragma once
/// \file utc_time.hpp
/// UTC calendar arithmetic of the navigation logs: times are seconds since
/// 1970-01-01T00:00:00Z (UTC, no leap seconds, as POSIX time), dates days since 1970-01-01,
/// on the proleptic Gregorian calendar (H. Hinnant's civil-date algorithms).
#include <cstdint>
#include <string>

namespace meridian::nav {

/// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(int year, int month, int day);

/// "YYYY-MM-DDThh:mm:ss.sssZ" of seconds since 1970-01-01T00:00:00Z (milliseconds rounded).
std::string iso8601_utc(double unix_s);

}  // namespace meridian::nav
