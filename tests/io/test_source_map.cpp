// io::SourceMap: a library error's field path → the file, line and column the user wrote,
// the error's class kept. Expected places written out by hand from the rules in source_map.hpp.
#include <gtest/gtest.h>

#include "meridian/io/source_map.hpp"

namespace {

using meridian::ErrorContext;
using meridian::InputError;
using meridian::NumericalError;
using meridian::ParseError;
using meridian::io::SourceMap;

// What located(sources, body) lets out when body throws E with field `field`.
template <class E>
std::string located_what(const SourceMap& s, const std::string& field, const std::string& file = {}) {
  try {
    meridian::io::located(s, [&]() -> int { throw E("bad", ErrorContext{file, std::nullopt, field}); });
  } catch (const E& e) {
    return e.what();
  }
  return "the class was lost";
}

SourceMap job() {
  SourceMap s;
  s.add_document("job.yaml", {{"", 1}, {"options", 3}, {"options.sigma_m", 4}, {"line", 7},
                              {"line.determinations", 8}, {"line.determinations[1]", 20},
                              {"line.determinations[1].crossings", 22}});
  s.add_document("options", "job.yaml", {{"sigma_m", 4}, {"alpha", 5}});
  s.add_rows("dr", {{"dr.csv", 4}, {"dr.csv", 5}, {"dr2.csv", 2}},
             [](const std::string& m) { return m == "speed_m_s" ? std::string("speed") : m; });
  s.add_rows("samples", [](std::size_t k, const std::string& member) {
    return ErrorContext{"line.bin", std::nullopt, "sample " + std::to_string(k) + (member.empty() ? "" : ": " + member)};
  });
  s.add_rows("position1.time_s", {{"p1.csv", 3}, {"p1.csv", 4}}, [](const std::string&) { return std::string("time"); });
  s.add_place("position1", {"p1.csv", std::nullopt, "position1"});
  s.add_place("initial", {"job.yaml", 12, ""});
  return s;
}

TEST(SourceMap, DocumentFieldsGetTheLineOfTheInnermostKey) {
  const SourceMap s = job();
  EXPECT_EQ(located_what<InputError>(s, "line.determinations[1].crossings[0].times_s"),
            "job.yaml:22: line.determinations[1].crossings[0].times_s: bad");
  EXPECT_EQ(located_what<InputError>(s, "line.determinations[0]"), "job.yaml:8: line.determinations[0]: bad");
  // "line.x" is under "line"; "linear" is not (only '.', '[' continue a key).
  EXPECT_EQ(located_what<InputError>(s, "line.x"), "job.yaml:7: line.x: bad");
  EXPECT_EQ(located_what<InputError>(s, "linear"), "job.yaml: linear: bad");
  // An error without a field belongs to the job's document.
  EXPECT_EQ(located_what<NumericalError>(s, ""), "job.yaml:1: bad");
}

TEST(SourceMap, PrefixedDocumentMapsInputFieldsToKeys) {
  EXPECT_EQ(located_what<InputError>(job(), "options.alpha"), "job.yaml:5: alpha: bad");
}

TEST(SourceMap, RowsNameFileLineAndColumn) {
  const SourceMap s = job();
  EXPECT_EQ(located_what<ParseError>(s, "dr[1].speed_m_s"), "dr.csv:5: speed: bad");
  EXPECT_EQ(located_what<ParseError>(s, "dr[2].heading_deg"), "dr2.csv:2: heading_deg: bad");
  EXPECT_EQ(located_what<ParseError>(s, "dr[0]"), "dr.csv:4: bad");
  // Beyond the rows: the next rule (the document) takes it.
  EXPECT_EQ(located_what<ParseError>(s, "dr[7].speed_m_s"), "job.yaml: dr[7].speed_m_s: bad");
  EXPECT_EQ(located_what<NumericalError>(s, "samples[40].lat_rad"), "line.bin: sample 40: lat_rad: bad");
  EXPECT_EQ(located_what<NumericalError>(s, "samples 41"), "line.bin: sample 41: bad");
  EXPECT_EQ(located_what<InputError>(s, "position1.time_s[1]"), "p1.csv:4: time: bad");
  EXPECT_EQ(located_what<InputError>(s, "position1.current_A"), "p1.csv: position1: bad");
}

TEST(SourceMap, PlacesAndErrorsThatNameAFile) {
  const SourceMap s = job();
  EXPECT_EQ(located_what<InputError>(s, "initial.sigma_m"), "job.yaml:12: bad");
  // A reader's own error already names its file: unchanged.
  EXPECT_EQ(located_what<ParseError>(s, "dr[1].speed_m_s", "other.csv"), "other.csv: dr[1].speed_m_s: bad");
  // No rule: the field stays and no file is invented.
  EXPECT_EQ(located_what<InputError>(SourceMap(), "x"), "x: bad");
}

}  // namespace
