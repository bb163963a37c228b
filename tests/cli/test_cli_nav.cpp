// Runs `meridian nav inspect` as a hydrographer would: a log with problems (text and JSON, the
// keys of issue 9), several files, the missing-checksum option, an unreadable file, and the six
// real logs of ../shared/data/nmea (skipped when that folder is absent).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using meridian_test::CmdResult;
class NavCli : public meridian_test::CliTest {};

// Checksums worked out by hand (XOR of the bytes between $ and *): HEHDT,218.53,T → 12 (as in
// nbp1406-gyro.nmea line 1).
const char* kLog =
    "2014-08-01T00:00:00.183000Z $HEHDT,218.53,T*12\n"
    "2014-08-01T00:00:00.383000Z $HEHDT,218.53,T*13\n"  // bad checksum
    "2014-08-01T00:00:00.583000Z $HEHDT,218.53,T\n"     // no checksum
    "2014-08-01T00:00:00.783000Z $HEHDT,218.5\n"        // truncated (no checksum either)
    "2014-08-01T00:00:00.983000Z $HEHDT,218.53,T*1\n"   // truncated in the checksum: malformed
    "$PSXN,22,-0.12,-0.80*32\n";                         // proprietary (from the seapath log)

}  // namespace

TEST_F(NavCli, InspectReportsEveryProblemWithLines) {
  write("log.nmea", kLog);
  const CmdResult r = run("nav inspect log.nmea --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out)["files"][0];
  EXPECT_EQ(j["file"], "log.nmea");
  EXPECT_EQ(j["lines"], 6);
  EXPECT_EQ(j["sentences"], nlohmann::json({{"HEHDT", 1}}));
  EXPECT_EQ(j["proprietary"], 1);
  EXPECT_EQ(j["bad_checksum"], 1);
  EXPECT_EQ(j["bad_checksum_lines"], nlohmann::json({2}));
  EXPECT_EQ(j["no_checksum"], 2);
  EXPECT_EQ(j["no_checksum_lines"], nlohmann::json({3, 4}));
  EXPECT_EQ(j["malformed"], 1);
  EXPECT_EQ(j["malformed_lines"][0]["line"], 5);
  EXPECT_EQ(j["duplicates"], 0);
  EXPECT_EQ(j["unknown"], 0);
  EXPECT_EQ(j["first_time"], "2014-08-01T00:00:00.183Z");  // the logger stamp: HDT has no time
  EXPECT_EQ(j["time_source"], "logger");
  EXPECT_EQ(j["gps_week_rollover_suspected"], false);
  for (const char* key : {"sentences", "proprietary", "bad_checksum", "no_checksum", "duplicates", "first_time",
                          "last_time", "file", "lines", "unknown", "malformed", "gps_week_rollover_suspected"})
    EXPECT_TRUE(j.contains(key)) << key;
  // accepted under the option: the two sentences without checksum count, with a warning
  const CmdResult a = run("nav inspect log.nmea --json --accept-missing-checksum");
  ASSERT_EQ(a.code, 0) << a.err;
  const auto ja = nlohmann::json::parse(a.out)["files"][0];
  EXPECT_EQ(ja["sentences"]["HEHDT"], 3);
  EXPECT_FALSE(ja["warnings"].empty());
  // the text summary names the lines
  const CmdResult t = run("nav inspect log.nmea");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("bad checksum: 1 (lines 2)"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("line 5:"), std::string::npos) << t.out;
}

TEST_F(NavCli, UnreadableFileFailsNamingIt) {
  write("log.nmea", kLog);
  const CmdResult r = run("nav inspect log.nmea missing.nmea");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("missing.nmea"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());  // nothing half printed
}

TEST_F(NavCli, SixRealLogs) {
  const std::filesystem::path d = std::filesystem::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "data" / "nmea";
  if (!std::filesystem::is_directory(d)) GTEST_SKIP() << d << " is absent";
  std::string args = "nav inspect --json";
  for (const char* f : {"nbp1406-seapath330.nmea", "nbp1406-gyro.nmea", "nbp1406-pcode-gps-rollover.nmea",
                        "nbp1406-gps-nochecksum.nmea", "bg-zeus2-ijsselmeer.nmea", "plaka-sailboat-4h.nmea"})
    args += " " + (d / f).string();
  const CmdResult r = run(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto files = nlohmann::json::parse(r.out)["files"];
  ASSERT_EQ(files.size(), 6u);
  EXPECT_EQ(files[0]["sentences"]["INGGA"], 625);  // grep -c '\$INGGA'
  EXPECT_EQ(files[0]["proprietary"], 1875);        // grep -c '\$PSXN'
  EXPECT_EQ(files[1]["sentences"]["HEHDT"], 5000); // grep -c '\$HEHDT'
  for (std::size_t k = 0; k < files.size(); ++k)
    EXPECT_EQ(files[k]["gps_week_rollover_suspected"], k == 2) << files[k]["file"];
  EXPECT_EQ(files[3]["no_checksum"], 5000);  // wc -l; grep -c '\*' → 0
  EXPECT_EQ(files[4]["duplicates_by_type"]["GPRMC"], 1);
  EXPECT_TRUE(files[5]["first_time"].is_null());  // plaka: no date anywhere
}
