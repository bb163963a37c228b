// The streaming record reader: comments, headers and units, delimiters,
// CRLF, chunking, error locations and a long stream. Expected records are
// written out by hand (or generated alongside the text), never taken from
// the reader's own output.

#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/record_reader.hpp"

using namespace meridian;
using namespace meridian::io;

namespace {

struct Rec {
  int line;
  std::vector<std::string> fields;
  bool operator==(const Rec&) const = default;
};

// Every record of `text`, read `chunk` records at a time.
std::vector<Rec> read_all(const std::string& text, std::size_t chunk, RecordFormat format = {},
                          std::vector<Column>* header = nullptr) {
  std::istringstream in(text);
  RecordReader r(in, "t.csv", format);
  RecordChunk c;
  std::vector<Rec> out;
  while (r.next(c, chunk)) {
    EXPECT_LE(c.size(), chunk);
    for (std::size_t i = 0; i < c.size(); ++i) {
      Rec x{c[i].line(), {}};
      for (std::size_t k = 0; k < c[i].size(); ++k) x.fields.emplace_back(c[i][k]);
      out.push_back(x);
    }
  }
  if (header) *header = r.header();
  EXPECT_EQ(r.bytes_read(), text.size());
  return out;
}

// Throws meridian::Error with exactly this message (file:line: field: text).
auto throws(const char* message) { return testing::ThrowsMessage<Error>(testing::StrEq(message)); }

// Reading all of `text`, for throws().
auto reading(const std::string& text, RecordFormat format = {}) {
  return [text, format] { read_all(text, 10, format); };
}

TEST(RecordReader, SkipsCommentsAndBlankLinesAndKeepsFileLineNumbers) {
  const std::string text =
      "# survey line 7\n\n  # indented comment\n1,2,3  # trailing\n\t\n4, 5 ,6\n# end\n";
  const auto recs = read_all(text, 100);
  ASSERT_EQ(recs.size(), 2u);
  EXPECT_EQ(recs[0], (Rec{4, {"1", "2", "3"}}));
  EXPECT_EQ(recs[1], (Rec{6, {"4", "5", "6"}}));
}

TEST(RecordReader, HeaderWithAndWithoutUnits) {
  std::vector<Column> h;
  auto recs = read_all("lat [deg], lon[deg] ,h [ m ],name\n1,2,3,P1\n", 10, {}, &h);
  ASSERT_EQ(h.size(), 4u);
  EXPECT_EQ(h[0].name, "lat");
  EXPECT_EQ(h[0].unit, "deg");
  EXPECT_EQ(h[1].name, "lon");
  EXPECT_EQ(h[1].unit, "deg");
  EXPECT_EQ(h[2].name, "h");
  EXPECT_EQ(h[2].unit, "m");
  EXPECT_EQ(h[3].name, "name");
  EXPECT_EQ(h[3].unit, "");
  ASSERT_EQ(recs.size(), 1u);
  EXPECT_EQ(recs[0], (Rec{2, {"1", "2", "3", "P1"}}));

  // Suffixes are part of the name; no unit.
  read_all("lat_deg,lon_deg\n1,2\n", 10, {}, &h);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].name, "lat_deg");
  EXPECT_EQ(h[0].unit, "");

  // Whitespace header: a bracketed unit standing apart joins its name.
  recs = read_all("lat [deg]  lon [deg] h[m]\n1 2 3\n", 10, {}, &h);
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[1].name, "lon");
  EXPECT_EQ(h[1].unit, "deg");
  EXPECT_EQ(h[2].unit, "m");
  EXPECT_EQ(recs[0], (Rec{2, {"1", "2", "3"}}));

  // No header: a data line begins with a number; a point name in the first
  // column does not make a header when other fields are numbers.
  recs = read_all("P1,37.5,112\nP2,37.6,112\n", 10, {}, &h);
  EXPECT_TRUE(h.empty());
  EXPECT_EQ(recs.size(), 2u);
  recs = read_all("-1,2\n", 10, {}, &h);
  EXPECT_TRUE(h.empty());
  EXPECT_EQ(recs.size(), 1u);
}

TEST(RecordReader, ExplicitHeaderModes) {
  std::vector<Column> h;
  auto recs = read_all("a,b\n1,2\n", 10, {Delimiter::Auto, HeaderMode::Absent}, &h);
  EXPECT_TRUE(h.empty());
  EXPECT_EQ(recs.size(), 2u);
  recs = read_all("1,2\n3,4\n", 10, {Delimiter::Auto, HeaderMode::Present}, &h);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].name, "1");
  EXPECT_EQ(recs.size(), 1u);
  EXPECT_THAT(reading("# nothing\n", {Delimiter::Auto, HeaderMode::Present}),
              throws("t.csv: no header line: the input has no line of column names"));
}

TEST(RecordReader, FindsColumnsByNameIgnoringCase) {
  std::istringstream in("Lat [deg],LON [deg],h_m\n1,2,3\n");
  RecordReader r(in, "p.csv");
  EXPECT_EQ(r.find_column("lat"), std::optional<std::size_t>(0));
  EXPECT_EQ(r.require_column("lon"), 1u);
  EXPECT_EQ(r.find_column("h"), std::nullopt);
  EXPECT_THAT(([&] { r.require_column("x"); }),
              throws("p.csv:1: no column \"x\" in the header (columns: Lat, LON, h_m)"));
  RecordChunk c;
  ASSERT_TRUE(r.next(c, 5));
  EXPECT_EQ(c[0].field_name(2), "h_m");
  EXPECT_EQ(c[0].field_name(5), "column 6");
}

TEST(RecordReader, WhitespaceCommaAndSemicolon) {
  EXPECT_EQ(read_all(" 1\t 2   3 \n", 10), (std::vector<Rec>{{1, {"1", "2", "3"}}}));
  EXPECT_EQ(read_all("1 ,, 3,\n", 10), (std::vector<Rec>{{1, {"1", "", "3", ""}}}));
  EXPECT_EQ(read_all("1;2 5;3\n", 10), (std::vector<Rec>{{1, {"1", "2 5", "3"}}}));
  // The first data line decides; later lines are split the same way.
  EXPECT_EQ(read_all("37 30 00,112\n1 2,3\n", 10),
            (std::vector<Rec>{{1, {"37 30 00", "112"}}, {2, {"1 2", "3"}}}));
  // An explicit delimiter wins.
  EXPECT_EQ(read_all("1,2 3\n", 10, {Delimiter::Whitespace, HeaderMode::Auto}),
            (std::vector<Rec>{{1, {"1,2", "3"}}}));
  std::istringstream in("lat lon\n1 2\n");
  RecordReader r(in, "w.txt");
  EXPECT_EQ(r.delimiter(), Delimiter::Auto);
  EXPECT_EQ(r.header().size(), 2u);
  EXPECT_EQ(r.delimiter(), Delimiter::Whitespace);
}

TEST(RecordReader, CrlfByteOrderMarkAndNoFinalNewline) {
  EXPECT_EQ(read_all("\xEF\xBB\xBFlat,lon\r\n1,2\r\n\r\n# c\r\n3,4\r\n", 10),
            (std::vector<Rec>{{2, {"1", "2"}}, {5, {"3", "4"}}}));
  EXPECT_EQ(read_all("1 2\r\n3 4", 10), (std::vector<Rec>{{1, {"1", "2"}}, {2, {"3", "4"}}}));
  std::vector<Column> h;
  read_all("lat [deg]\r\n", 10, {}, &h);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0].unit, "deg");
}

TEST(RecordReader, EmptyInputs) {
  for (const std::string text : {"", "\n\n", "# only comments\n#\n", "lat,lon\n", "\r\n  \t\r\n"}) {
    std::vector<Column> h;
    EXPECT_TRUE(read_all(text, 3, {}, &h).empty()) << text;
  }
}

TEST(RecordReader, SameRecordsWhateverTheChunkSize) {
  std::string text = "# generated\nx [m],y [m]\n";
  std::vector<Rec> expected;
  int line = 2;
  for (int i = 0; i < 103; ++i) {
    if (i % 7 == 0) {
      text += "# comment\n";
      ++line;
    }
    if (i % 11 == 0) {
      text += "\n";
      ++line;
    }
    text += std::to_string(i) + "," + std::to_string(i * i) + "\n";
    expected.push_back({++line, {std::to_string(i), std::to_string(i * i)}});
  }
  for (std::size_t chunk : {1u, 2u, 3u, 7u, 50u, 102u, 103u, 104u, 1000u})
    EXPECT_EQ(read_all(text, chunk), expected) << "chunk " << chunk;
}

TEST(RecordReader, ChunkSizeZeroIsRefused) {
  std::istringstream in("1\n");
  RecordReader r(in, "z.csv");
  RecordChunk c;
  EXPECT_THROW(r.next(c, 0), InputError);
}

TEST(RecordReader, NumberAndAngleHelpers) {
  std::istringstream in("lat,lon,h_m\n37 50 24,-0.5,+1.5e2\n1,2,5x\n1,2,nan\n1,2,\n1,2\n1,abc,3\n");
  RecordReader r(in, "points.csv");
  RecordChunk c;
  ASSERT_TRUE(r.next(c, 100));
  ASSERT_EQ(c.size(), 6u);
  EXPECT_NEAR(c[0].angle(0).deg(), 37.84, 1e-12);
  EXPECT_NEAR(c[0].angle(1).rad(), -0.5 * units::kDegree, 1e-15);
  EXPECT_EQ(c[0].number(2), 150.0);
  EXPECT_THAT(([&] { c[1].number(2); }), throws("points.csv:3: h_m: \"5x\" is not a number"));
  EXPECT_THAT(([&] { c[2].number(2); }), throws("points.csv:4: h_m: \"nan\" is not a number"));
  EXPECT_THAT(([&] {
                c[3].number(2, {"h", "height"});
              }),
              throws("points.csv:5: h: height \"\" is not a number"));
  EXPECT_THAT(([&] { c[4].number(2); }),
              throws("points.csv:6: h_m: missing: the line has only 2 fields"));
  EXPECT_THAT(([&] { c[5].angle(1); }),
              throws("points.csv:7: lon: cannot read angle \"abc\": unexpected \"abc\""));
  EXPECT_THAT(([&] { c[5].angle(1, {"longitude"}); }),
              throws("points.csv:7: longitude: cannot read angle \"abc\": unexpected \"abc\""));
  // Any parser: its errors get the record's place; a field it names is kept.
  EXPECT_THAT(
      ([&] { c[5].parse(2, [](std::string_view) -> int { throw InputError("too big"); }); }),
      throws("points.csv:7: h_m: too big"));
  EXPECT_THAT(([&] {
                c[5].parse(2, [](std::string_view) -> int {
                  throw InputError("too big", {"", {}, "height"});
                });
              }),
              throws("points.csv:7: height: too big"));
  EXPECT_EQ(c[5].parse(2, [](std::string_view t) { return std::string(t) + "!"; }), "3!");
}

TEST(RecordReader, ColumnIndexWhenThereIsNoHeader) {
  std::istringstream in("1 2 x\n");
  RecordReader r(in, "<stdin>");
  RecordChunk c;
  ASSERT_TRUE(r.next(c, 1));
  EXPECT_THAT(([&] { c[0].number(2); }), throws("<stdin>:1: column 3: \"x\" is not a number"));
}

TEST(RecordReader, FiniteDoubles) {
  for (const char* ok : {"0", "-0.5", "+3e-4", ".5", "5.", "1E3", "123456789012"})
    EXPECT_TRUE(to_finite_double(ok).has_value()) << ok;
  for (const char* bad :
       {"", "+", "-", "+-1", "1e", "0x10", " 1", "1 ", "nan", "inf", "-infinity", "1e999", "1,5"})
    EXPECT_FALSE(to_finite_double(bad).has_value()) << bad;
  EXPECT_EQ(*to_finite_double("+2.5"), 2.5);
}

TEST(RecordReader, BadHeadersNameTheLineAndColumn) {
  EXPECT_THAT(reading("# c\nlat,lon,LAT\n1,2,3\n"),
              throws("t.csv:2: column \"LAT\" appears twice in the header"));
  EXPECT_THAT(
      reading("lat,lon [deg\n1,2\n"),
      throws("t.csv:1: column 2: header field \"lon [deg\": the unit's \"[\" is not closed"));
  EXPECT_THAT(
      reading("lat,lon [deg] x\n1,2\n"),
      throws("t.csv:1: column 2: header field \"lon [deg] x\": text after the unit's \"]\""));
  EXPECT_EQ(parse_column(" dg [ mGal ] ").name, "dg");
  EXPECT_EQ(parse_column(" dg [ mGal ] ").unit, "mGal");
  EXPECT_THROW(parse_column("[deg]"), ParseError);
}

TEST(RecordReader, LongStreamKeepsCountsAndBytes) {
  // 10^6 generated rows: the reader must see every one, in order, with the
  // right line numbers, whatever the chunk size.
  constexpr int kRows = 1000000;
  std::string text = "t [s] x [m]\n";
  text.reserve(16u * kRows);
  for (int i = 0; i < kRows; ++i) {
    text += std::to_string(i);
    text += ' ';
    text += std::to_string(i % 997);
    text += '\n';
  }
  std::istringstream in(text);
  RecordReader r(in, "long.txt");
  RecordChunk c;
  long count = 0, sum_x = 0, expected_x = 0;
  bool in_order = true;
  while (r.next(c, 16384)) {
    for (std::size_t i = 0; i < c.size(); ++i) {
      in_order = in_order && c[i].line() == count + 2 && c[i][0] == std::to_string(count);
      sum_x += static_cast<long>(c[i].number(1));
      expected_x += count % 997;
      ++count;
    }
  }
  EXPECT_EQ(count, kRows);
  EXPECT_TRUE(in_order);
  EXPECT_EQ(sum_x, expected_x);
  EXPECT_EQ(r.bytes_read(), text.size());
  EXPECT_EQ(r.lines_read(), kRows + 1);
}

}  // namespace
