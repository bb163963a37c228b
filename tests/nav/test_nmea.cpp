// The NMEA 0183 reader (io/nmea.hpp): a catalogue of malformed sentences built here, values
// decoded by hand in the comments, and the six real logs of ../shared/data/nmea with counts
// taken independently with grep/awk (the command beside each number).

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/io/nmea.hpp"

namespace {

namespace nmea = meridian::io::nmea;
namespace fs = std::filesystem;
constexpr double kDeg = std::numbers::pi / 180.0;

// "$" + body + "*HH", the checksum computed here (XOR of the body's bytes).
std::string with_sum(const std::string& body, bool lower = false) {
  unsigned x = 0;
  for (char c : body) x ^= static_cast<unsigned char>(c);
  const char* digits = lower ? "0123456789abcdef" : "0123456789ABCDEF";
  return "$" + body + "*" + digits[x >> 4] + digits[x & 15];
}

struct Read {
  nmea::Summary summary;
  std::vector<nmea::Sentence> sentences;
};

Read read_text(const std::string& text, nmea::Options o = {}) {
  std::istringstream in(text);
  Read r;
  r.summary = nmea::read(in, "test.nmea", o, [&](const nmea::Sentence& s) { r.sentences.push_back(s); });
  return r;
}

fs::path data_dir() { return fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "data" / "nmea"; }

Read read_data(const std::string& name, nmea::Options o = {}) {
  Read r;
  r.summary = nmea::read_file((data_dir() / name).string(), o,
                              [&](const nmea::Sentence& s) { r.sentences.push_back(s); });
  return r;
}

#define SKIP_WITHOUT_DATA() \
  if (!fs::is_directory(data_dir())) GTEST_SKIP() << data_dir() << " is absent"

}  // namespace

// --- values decoded by hand ---------------------------------------------------------------

TEST(NmeaValues, GgaDecodedByHand) {
  // $GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47 (the NMEA textbook fix):
  // 12:35:19 = 12·3600 + 35·60 + 19 = 45319 s; 4807.038,N = 48° + 7.038′/60 = 48.1173° N;
  // 01131.000,E = 11° + 31′/60 = 11.516667° E; quality 1, 8 satellites, HDOP 0.9, 545.4 m.
  const Read r = read_text("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\n");
  ASSERT_EQ(r.sentences.size(), 1u);
  EXPECT_EQ(r.summary.bad_checksum, 0);  // 0x47 is the published checksum
  const auto& g = std::get<nmea::Gga>(r.sentences[0].data);
  EXPECT_DOUBLE_EQ(*g.time_of_day_s, 45319.0);
  EXPECT_NEAR(*g.lat_rad, 48.1173 * kDeg, 1e-12);
  EXPECT_NEAR(*g.lon_rad, (11.0 + 31.0 / 60.0) * kDeg, 1e-12);
  EXPECT_EQ(*g.fix_quality, 1);
  EXPECT_EQ(*g.satellites, 8);
  EXPECT_DOUBLE_EQ(*g.hdop, 0.9);
  EXPECT_DOUBLE_EQ(*g.altitude_m, 545.4);
  EXPECT_EQ(r.sentences[0].talker, "GP");
  EXPECT_FALSE(r.sentences[0].time_s);  // no date yet
}

TEST(NmeaValues, SouthWestSpeedsAndHeading) {
  // 2200.110899,S = −(22° + 0.110899′/60); 01756.359432,W = −(17° + 56.359432′/60).
  // VTG 215.11,T … 9.1,N → 9.1·1852/3600 = 4.681444 m/s. HDT 218.53 → 218.53°.
  // VBW 5.0,-0.5,A,4.8,-0.4,V: water 5.0 kn forward, 0.5 kn to port, valid; ground invalid.
  const std::string text = with_sum("INGGA,000000.16,2200.110899,S,01756.359432,W,1,12,0.7,-2.76,M,4.67,M,,") +
                           "\n" + with_sum("INVTG,215.11,T,239.79,M,9.1,N,16.9,K,A") + "\n" +
                           with_sum("HEHDT,218.53,T") + "\n" + with_sum("VMVBW,5.0,-0.5,A,4.8,-0.4,V") + "\n" +
                           with_sum("GPVTG,10.0,T,,M,,N,36.0,K") + "\n";
  const Read r = read_text(text);
  ASSERT_EQ(r.sentences.size(), 5u);
  const auto& g = std::get<nmea::Gga>(r.sentences[0].data);
  EXPECT_NEAR(*g.lat_rad, -(22.0 + 0.110899 / 60.0) * kDeg, 1e-13);
  EXPECT_NEAR(*g.lon_rad, -(17.0 + 56.359432 / 60.0) * kDeg, 1e-13);
  EXPECT_DOUBLE_EQ(*g.altitude_m, -2.76);
  const auto& v = std::get<nmea::Vtg>(r.sentences[1].data);
  EXPECT_NEAR(*v.course_true_rad, 215.11 * kDeg, 1e-13);
  EXPECT_NEAR(*v.speed_m_s, 4.681444, 1e-6);
  EXPECT_NEAR(*std::get<nmea::Hdt>(r.sentences[2].data).heading_rad, 218.53 * kDeg, 1e-13);
  const auto& w = std::get<nmea::Vbw>(r.sentences[3].data);
  EXPECT_NEAR(*w.water_longitudinal_m_s, 5.0 * 1852.0 / 3600.0, 1e-12);
  EXPECT_NEAR(*w.water_transverse_m_s, -0.5 * 1852.0 / 3600.0, 1e-12);
  EXPECT_TRUE(*w.water_valid);
  EXPECT_FALSE(*w.ground_valid);
  // speed only in km/h: 36 km/h = 10 m/s
  EXPECT_NEAR(*std::get<nmea::Vtg>(r.sentences[4].data).speed_m_s, 10.0, 1e-12);
}

TEST(NmeaValues, DatesGiveTimesAcrossMidnight) {
  // RMC 235959 on 31 Dec 2013 → 2013-12-31T23:59:59Z; the GGA 000001 after it is the next day,
  // a ZDA of 1 Jan 2014 then a GGA of 235958 (logged late) goes back to the 31st.
  const std::string text = with_sum("GPRMC,235959,A,4807.038,N,01131.000,E,5.0,90.0,311213,,") + "\n" +
                           with_sum("GPGGA,000001,4807.038,N,01131.000,E,1,08,0.9,545.4,M,,M,,") + "\n" +
                           with_sum("GPZDA,000002.00,01,01,2014,00,00") + "\n" +
                           with_sum("GPGGA,235958,4807.038,N,01131.000,E,1,08,0.9,545.4,M,,M,,") + "\n";
  const Read r = read_text(text);
  ASSERT_EQ(r.sentences.size(), 4u);
  const double day = static_cast<double>(nmea::days_from_civil(2013, 12, 31)) * 86400.0;
  EXPECT_EQ(nmea::days_from_civil(1970, 1, 1), 0);
  EXPECT_EQ(nmea::days_from_civil(2000, 3, 1), 11017);  // 30 years (7 leap days) + Jan + Feb 2000
  EXPECT_DOUBLE_EQ(*r.sentences[0].time_s, day + 86399.0);
  EXPECT_DOUBLE_EQ(*r.sentences[1].time_s, day + 86401.0);
  EXPECT_DOUBLE_EQ(*r.sentences[2].time_s, day + 86402.0);
  EXPECT_DOUBLE_EQ(*r.sentences[3].time_s, day + 86398.0);
  EXPECT_EQ(nmea::iso8601_utc(*r.sentences[1].time_s), "2014-01-01T00:00:01.000Z");
  EXPECT_EQ(*r.summary.first_time_s, day + 86398.0);  // the earliest, not the first logged
  EXPECT_EQ(*r.summary.last_time_s, day + 86402.0);
  EXPECT_FALSE(r.summary.gps_week_rollover_suspected);
}

// --- the catalogue of malformed sentences ---------------------------------------------------

TEST(NmeaCatalogue, EachProblemCountedWithItsLine) {
  const std::string good = with_sum("HEHDT,218.53,T");
  std::string bad_sum = good;
  bad_sum.back() = bad_sum.back() == '0' ? '1' : '0';
  const std::string lines[] = {
      good,                                       // 1 accepted
      bad_sum,                                    // 2 bad checksum
      "$HEHDT,218.53,T",                          // 3 no checksum
      good.substr(0, good.size() - 1),            // 4 truncated in the checksum: malformed
      "$HEHDT,218.53,T*ZZ",                       // 5 non-hex checksum: malformed
      with_sum("HEHDT,,T"),                       // 6 empty heading: accepted, missing
      with_sum("GPGGA,123519,4807.038,N"),        // 7 too few fields: malformed
      "\x01\x02garbage$\x7f\x10*00",              // 8 garbage bytes: malformed
      "$HEHDT,218.5\xc3\xa9,T*00",                // 9 non-ASCII (UTF-8 é): malformed
      "$" + std::string(5000, 'A') + "*00",       // 10 overlong: malformed, not stored
      "$",                                        // 11 "$" alone: malformed
      with_sum("HEHDT,100.00,T", true),           // 12 lower-case checksum: accepted
      "2014-08-01T00:00:00.183000Z " + with_sum("HEHDT,120.00,T"),  // 13 logger prefix
      "# a comment",                              // 14
      "",                                         // 15 blank
      with_sum("PSXN,22,-0.12,-0.80"),            // 16 proprietary
      with_sum("GPGSV,3,1,12"),                   // 17 valid, type not decoded
      with_sum("GPGGA,123519,48x7.038,N,01131.000,E,1,08,0.9,545.4,M,,M,,"),  // 18 bad number
      "$GPGGA,1235$HEHDT,218.53,T*" + good.substr(good.size() - 2),  // 19 two sentences joined
      with_sum("HEHDT,130.00,T"),                 // 20 no final newline (below)
  };
  std::string text;
  for (const auto& l : lines) text += l + "\r\n";
  text.resize(text.size() - 2);
  const Read r = read_text(text);
  const nmea::Summary& s = r.summary;
  EXPECT_EQ(s.lines, 20);
  EXPECT_EQ(s.bad_checksum, 1);
  EXPECT_EQ(s.bad_checksum_lines, std::vector<int>{2});
  EXPECT_EQ(s.no_checksum, 1);
  EXPECT_EQ(s.no_checksum_lines, std::vector<int>{3});
  std::vector<int> malformed;
  for (const auto& [line, reason] : s.malformed_lines) malformed.push_back(line);
  EXPECT_EQ(malformed, (std::vector<int>{4, 5, 7, 8, 9, 10, 11, 18, 19}));
  EXPECT_EQ(s.malformed, 9);
  EXPECT_EQ(s.comments, 1);
  EXPECT_EQ(s.blank, 1);
  EXPECT_EQ(s.proprietary, 1);
  EXPECT_EQ(s.unknown, 1);
  EXPECT_EQ(s.logger_prefixed, 1);
  EXPECT_EQ(s.sentences.at("HEHDT"), 5);  // lines 1, 6, 12, 13, 20
  EXPECT_EQ(s.sentences.at("GPGSV"), 1);
  ASSERT_EQ(r.sentences.size(), 6u);
  EXPECT_FALSE(std::get<nmea::Hdt>(r.sentences[1].data).heading_rad);  // empty, never 0
  EXPECT_NEAR(*std::get<nmea::Hdt>(r.sentences[2].data).heading_rad, 100.0 * kDeg, 1e-13);
  EXPECT_EQ(r.sentences[3].line, 13);
  // 2014-08-01 is day 16283 since 1970 (44 years with 11 leap days: 16071, + 212 days to Aug 1)
  EXPECT_NEAR(*r.sentences[3].logger_time_s, 16283 * 86400.0 + 0.183, 1e-6);
  EXPECT_NEAR(*std::get<nmea::Hdt>(r.sentences[5].data).heading_rad, 130.0 * kDeg, 1e-13);
  EXPECT_EQ(r.sentences[5].line, 20);
  EXPECT_EQ(s.time_source, "logger");
}

TEST(NmeaCatalogue, MissingChecksumAcceptedUnderTheOption) {
  const std::string text = "$HEHDT,218.53,T\n$HEHDT,218.54,T\n";
  EXPECT_EQ(read_text(text).sentences.size(), 0u);
  nmea::Options o;
  o.accept_missing_checksum = true;
  const Read r = read_text(text, o);
  ASSERT_EQ(r.sentences.size(), 2u);
  EXPECT_FALSE(r.sentences[0].has_checksum);
  EXPECT_EQ(r.summary.no_checksum, 2);
  EXPECT_TRUE(r.summary.accept_missing_checksum);
  // a truncated GGA without checksum is malformed only, not also "accepted unverified"
  const Read t = read_text("$GPGGA,123519,4807.038,N\n", o);
  EXPECT_EQ(t.summary.malformed, 1);
  EXPECT_EQ(t.summary.no_checksum, 0);
}

TEST(NmeaCatalogue, ByteOrderMarkBeforeTheFirstLine) {
  const Read r = read_text("\xEF\xBB\xBF" + with_sum("HEHDT,218.53,T") + "\n");
  EXPECT_EQ(r.summary.malformed, 0);
  EXPECT_EQ(r.sentences.size(), 1u);
}

TEST(NmeaCatalogue, DuplicateFixAndRolloverWithoutStamp) {
  const std::string rmc = with_sum("GPRMC,001638.226,A,2202.1978,S,01758.2181,W,010.9,223.0,161294,24.9,W");
  const Read r = read_text(rmc + "\n" + rmc + "\n" + with_sum("HEHDT,1.0,T") + "\n" + with_sum("HEHDT,1.0,T"));
  EXPECT_EQ(r.summary.duplicates, 1);
  EXPECT_EQ(r.summary.duplicates_by_type.at("GPRMC"), 1);
  EXPECT_EQ(r.summary.sentences.at("GPRMC"), 2);
  EXPECT_EQ(r.sentences.size(), 3u);  // the repeated fix is not delivered, the steady heading is
  EXPECT_TRUE(r.summary.gps_week_rollover_suspected);  // 1994 without a logger stamp
  EXPECT_EQ(*r.summary.rollover_line, 1);
}

TEST(NmeaCatalogue, FileErrorsNameTheFile) {
  try {
    nmea::read_file("/nonexistent/log.nmea", {});
    FAIL();
  } catch (const meridian::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/log.nmea"), std::string::npos);
  }
  EXPECT_THROW(nmea::read_file(fs::temp_directory_path().string(), {}), meridian::IoError);
}

// --- the real logs ----------------------------------------------------------------------------

TEST(NmeaRealLogs, Seapath330) {
  SKIP_WITHOUT_DATA();
  const Read r = read_data("nbp1406-seapath330.nmea");
  const auto& s = r.summary;
  for (const char* k : {"INGGA", "INHDT", "INRMC", "INVTG", "INZDA"})
    EXPECT_EQ(s.sentences.at(k), 625) << k;  // grep -c '\$INGGA' … (625 each)
  EXPECT_EQ(s.sentences.size(), 5u);
  EXPECT_EQ(s.proprietary, 1875);  // grep -c '\$PSXN'
  EXPECT_EQ(s.logger_prefixed, 5000);  // wc -l (every line stamped)
  EXPECT_EQ(s.bad_checksum + s.no_checksum + s.malformed + s.duplicates, 0);
  EXPECT_FALSE(s.gps_week_rollover_suspected);
  EXPECT_EQ(nmea::iso8601_utc(*s.first_time_s), "2014-08-01T00:00:00.160Z");  // head -2: INGGA,000000.16 after INZDA,000000.17
  EXPECT_EQ(s.time_source, "sentences");
}

TEST(NmeaRealLogs, GyroLowerCaseChecksums) {
  SKIP_WITHOUT_DATA();
  const Read r = read_data("nbp1406-gyro.nmea");
  // grep -c '\$HEHDT' → 5000; grep -c '[*][0-9a-f]*[a-f][0-9a-f]*$' → 1512 lower-case sums
  EXPECT_EQ(r.summary.sentences.at("HEHDT"), 5000);
  EXPECT_EQ(r.summary.bad_checksum, 0);
  EXPECT_EQ(r.summary.time_source, "logger");  // HDT has no time
  EXPECT_EQ(nmea::iso8601_utc(*r.summary.last_time_s), "2014-08-01T00:16:40.076Z");  // tail -1
}

TEST(NmeaRealLogs, PcodeRolloverAndMidnight) {
  SKIP_WITHOUT_DATA();
  const Read r = read_data("nbp1406-pcode-gps-rollover.nmea");
  for (const char* k : {"GPGGA", "GPGLL", "GPRMC", "GPVTG", "GPZDA"})
    EXPECT_EQ(r.summary.sentences.at(k), 1000) << k;  // grep -c '\$GPGGA' … (1000 each)
  EXPECT_TRUE(r.summary.gps_week_rollover_suspected);  // ZDA 16 12 1994 logged 2014-08-01
  EXPECT_EQ(*r.summary.rollover_line, 1);
  // head -2: ZDA 000000.00 16 12 1994, then GGA 235959.226: the 15th, before the ZDA
  EXPECT_EQ(nmea::iso8601_utc(*r.summary.first_time_s), "1994-12-15T23:59:59.226Z");
  // the GGAs straddle midnight (235959.226 then 000000.226): times strictly increase
  std::optional<double> last;
  int gga = 0;
  for (const auto& s : r.sentences)
    if (std::holds_alternative<nmea::Gga>(s.data)) {
      ASSERT_TRUE(s.time_s) << s.line;
      if (last) {
        EXPECT_GT(*s.time_s, *last) << s.line;
      }
      last = s.time_s, ++gga;
    }
  EXPECT_EQ(gga, 1000);
}

TEST(NmeaRealLogs, HandheldWithoutChecksums) {
  SKIP_WITHOUT_DATA();
  const Read rejected = read_data("nbp1406-gps-nochecksum.nmea");
  EXPECT_EQ(rejected.summary.no_checksum, 5000);  // grep -c '\*' → 0 of wc -l 5000
  EXPECT_TRUE(rejected.summary.sentences.empty());
  // every sentence rejected, but the logger stamps still span the file (head -1, tail -1)
  ASSERT_TRUE(rejected.summary.first_time_s.has_value());
  EXPECT_EQ(rejected.summary.time_source, "logger");
  EXPECT_EQ(nmea::iso8601_utc(*rejected.summary.first_time_s), "2014-08-01T00:00:00.316Z");
  nmea::Options o;
  o.accept_missing_checksum = true;
  const Read r = read_data("nbp1406-gps-nochecksum.nmea", o);
  // grep -c '\$GPZDA' → 1667, '\$GPGLL' → 1667, '\$GPVTG' → 1666
  EXPECT_EQ(r.summary.sentences.at("GPZDA"), 1667);
  EXPECT_EQ(r.summary.sentences.at("GPGLL"), 1667);
  EXPECT_EQ(r.summary.sentences.at("GPVTG"), 1666);
  EXPECT_EQ(r.summary.malformed, 0);
  // line 2: $GPGLL,2200.097,S,01756.346,W (NMEA 1.x: no time, no status)
  const auto& gll = std::get<nmea::Gll>(r.sentences[1].data);
  EXPECT_NEAR(*gll.lat_rad, -(22.0 + 0.097 / 60.0) * kDeg, 1e-13);
  EXPECT_FALSE(gll.time_of_day_s);
  EXPECT_FALSE(r.summary.gps_week_rollover_suspected);
}

TEST(NmeaRealLogs, ZeusCommentsCrlfAndOneDuplicateRmc) {
  SKIP_WITHOUT_DATA();
  const Read r = read_data("bg-zeus2-ijsselmeer.nmea");
  const auto& s = r.summary;
  EXPECT_EQ(s.lines, 5009);      // wc -l
  EXPECT_EQ(s.comments, 10);     // grep -c '^#'
  EXPECT_EQ(s.sentences.size(), 22u);  // grep '^\$' | cut -d, -f1 | sort -u | wc -l
  EXPECT_EQ(s.sentences.at("GPRMC"), 146);  // grep -c '\$GPRMC'
  EXPECT_EQ(s.sentences.at("SDHDG"), 1457);  // grep -c '\$SDHDG'
  EXPECT_EQ(s.sentences.at("GPGGA"), 138);   // grep -c '\$GPGGA'
  // tr -d '\r' < FILE | awk '{s=$0; sub(/^[^$]*/,"",s); if (s=="") next; split(s,a,",");
  //   k=a[1]; if (last[k]==s) d[k]++; last[k]=s} END{for(k in d) print k, d[k]}'
  // on the timed types: GPRMC 1 (lines 4359 and 4369), GPZDA 8, GPGGA and GPGLL none
  EXPECT_EQ(s.duplicates_by_type.at("GPRMC"), 1);
  EXPECT_EQ(s.duplicates_by_type.at("GPZDA"), 8);
  EXPECT_EQ(s.duplicates, 9);
  EXPECT_EQ(s.bad_checksum + s.no_checksum + s.malformed, 0);
  EXPECT_EQ(nmea::iso8601_utc(*s.first_time_s), "2018-08-20T09:47:37.000Z");  // first ZDA 094737 20 08 2018
  EXPECT_FALSE(s.gps_week_rollover_suspected);
}

TEST(NmeaRealLogs, PlakaHeadingsMissingNotZero) {
  SKIP_WITHOUT_DATA();
  const Read r = read_data("plaka-sailboat-4h.nmea");
  const auto& s = r.summary;
  EXPECT_EQ(s.lines, 116000);  // grep -c '^\$' (wc -l says 115999: no final newline)
  EXPECT_EQ(s.sentences.at("IIHDT"), 14500);  // grep -c 'IIHDT' (all "$IIHDT,,T*0C")
  EXPECT_EQ(s.sentences.at("IIVTG"), 7250);   // grep -c 'IIVTG'
  EXPECT_EQ(s.sentences.size(), 15u);
  long headings = 0;
  for (const auto& st : r.sentences)
    if (const auto* h = std::get_if<nmea::Hdt>(&st.data)) {
      ++headings;
      EXPECT_FALSE(h->heading_rad) << st.line;
    }
  EXPECT_EQ(headings, 14500);
  EXPECT_FALSE(s.first_time_s);  // no date anywhere (ZDA date fields empty), no logger stamp
  EXPECT_FALSE(s.gps_week_rollover_suspected);
}
