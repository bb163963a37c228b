// The NMEA 0183 reader (io/nmea.hpp), with and without accept_missing_checksum: it never
// throws for content, every decoded angle and speed is finite and in range, an empty field is
// missing (not 0 by accident of parsing), and the counts add up to at most the lines read.
#include <cmath>
#include <sstream>
#include <variant>

#include "fuzz_support.hpp"
#include "meridian/io/nmea.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

void check_angle(const std::optional<double>& a, double limit, const char* what) {
  if (!a) return;
  meridian_fuzz::check_finite(*a, what);
  if (std::abs(*a) > limit + 1e-12) meridian_fuzz::finding(what);
}

void check_sentence(const meridian::io::nmea::Sentence& s) {
  using namespace meridian::io::nmea;
  if (const auto* g = std::get_if<Gga>(&s.data)) {
    check_angle(g->lat_rad, kPi / 2, "GGA latitude beyond 90 deg");
    check_angle(g->lon_rad, kPi, "GGA longitude beyond 180 deg");
  } else if (const auto* h = std::get_if<Hdt>(&s.data)) {
    if (h->heading_rad && !(*h->heading_rad >= 0.0 && *h->heading_rad < 2 * kPi + 1e-12))
      meridian_fuzz::finding("HDT heading outside [0, 2 pi)");
  } else if (const auto* v = std::get_if<Vtg>(&s.data)) {
    if (v->speed_m_s) meridian_fuzz::check_finite(*v->speed_m_s, "VTG speed not finite");
  }
  if (s.time_s) meridian_fuzz::check_finite(*s.time_s, "time not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian::io::nmea;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  for (bool accept : {false, true}) {
    std::istringstream in(bytes);
    Options o;
    o.accept_missing_checksum = accept;
    long delivered = 0;
    Summary s;
    try {
      s = read(in, "log.nmea", o, [&](const Sentence& st) {
        ++delivered;
        check_sentence(st);
      });
    } catch (...) {
      meridian_fuzz::finding("the reader threw for content");
    }
    long problems = s.bad_checksum + s.malformed + s.proprietary + s.comments + s.blank;
    if (!accept) problems += s.no_checksum;
    if (delivered + problems > s.lines) meridian_fuzz::finding("more sentences and problems than lines");
  }
  return 0;
}
