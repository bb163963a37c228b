// The `gravity points --report` document: sections, the statistics table,
// one map per mapped quantity with the thinned sample as its data, and the
// sign note. Expected counts follow from the input and the thinning rule.

#include <algorithm>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/units.hpp"
#include "meridian/gravity/points_summary.hpp"
#include "meridian/report/gravity_html.hpp"
#include "meridian/report/html.hpp"

using namespace meridian;
using namespace meridian::report;

namespace {

const Section* find_section(const Document& d, const std::string& id) {
  for (const auto& s : d.sections)
    if (s.id == id) return &s;
  return nullptr;
}

std::vector<const Plot*> plots(const Document& d) {
  std::vector<const Plot*> out;
  for (const auto& s : d.sections)
    for (const auto& b : s.blocks)
      if (const auto* p = std::get_if<Plot>(&b)) out.push_back(p);
  return out;
}

gravity::PointsSummary summary_of(int n, std::size_t capacity) {
  gravity::PointsSummary s(capacity);
  for (int i = 0; i < n; ++i) {
    gravity::FieldValues v{};
    v.xi_rad = (i % 7 - 3) * units::kArcsecond;
    v.eta_rad = (i % 5 - 2) * units::kArcsecond;
    v.geoid_m = 30 + 0.01 * i;
    s.add(gravity::GeodeticPoint{(45 + 1e-3 * i) * units::kDegree, (7 + 2e-3 * i) * units::kDegree,
                                 100.0},
          v);
  }
  return s;
}

const gravity::ModelInfo kModel{"synth60s1", "m.gfc", 60, 60, 3.986004415e14, 6378136.3, "tide_free", "fully_normalized", ""};

TEST(GravityPointsDocument, HasSummaryMapsAndDefinitions) {
  // The quantities a user maps: xi, eta and N, one map each.
  const std::vector<std::string> mapped = {"xi", "eta", "N"};
  for (int n : {1, 37, 250}) {
    const std::size_t capacity = 100;
    const auto s = summary_of(n, capacity);
    const Document d = gravity_points_document({"pts.csv", kModel, {}, s});
    ASSERT_NE(find_section(d, "summary"), nullptr);
    ASSERT_NE(find_section(d, "maps"), nullptr);
    ASSERT_NE(find_section(d, "definitions"), nullptr);
    const auto ps = plots(d);
    ASSERT_EQ(ps.size(), mapped.size()) << n;
    // Each map draws the thinned sample: ceil(n / k) points, k the smallest
    // power of two that brings it within the capacity.
    std::size_t k = 1;
    while ((static_cast<std::size_t>(n) + k - 1) / k > capacity) k *= 2;
    const std::size_t drawn = (static_cast<std::size_t>(n) + k - 1) / k;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      EXPECT_EQ(ps[i]->spec["data"]["values"].size(), drawn) << n;
      EXPECT_NE(ps[i]->spec["encoding"]["color"]["title"].get<std::string>().find(mapped[i]),
                std::string::npos);
      EXPECT_NE(ps[i]->caption.find(std::to_string(n)), std::string::npos) << ps[i]->caption;
      EXPECT_NE(ps[i]->caption.find(std::to_string(drawn)), std::string::npos) << ps[i]->caption;
    }
    if (html_reports_available()) {
      const std::string html = render_html(d);
      const std::regex spec("data-vega-spec=");
      EXPECT_EQ(std::distance(std::sregex_iterator(html.begin(), html.end(), spec),
                              std::sregex_iterator()),
                static_cast<long>(mapped.size()));
    }
  }
}

TEST(GravityPointsDocument, StatisticsTableAndHeader) {
  const auto s = summary_of(3, 100);  // xi = -3", -2", -1"; N = 30, 30.01, 30.02
  gravity::PointsOptions track;
  track.track_tolerance_rad = 1e-3 * units::kArcsecond;
  const Document d = gravity_points_document({"line.csv", {"m", "m.egm", 60, 360, 3.986004415e14, 6378136.3, "", "", ""}, track, s});
  const Section* sum = find_section(d, "summary");
  ASSERT_NE(sum, nullptr);
  const Table* stats = nullptr;
  for (const auto& b : sum->blocks)
    if (const auto* t = std::get_if<Table>(&b); t && !stats) stats = t;
  ASSERT_NE(stats, nullptr);
  ASSERT_EQ(stats->rows.size(), 3u);
  // min, max, mean, RMS, sd of xi: -3, -1, -2, sqrt(14/3), 1.
  EXPECT_EQ(stats->rows[0][2], "-3.0000");
  EXPECT_EQ(stats->rows[0][3], "-1.0000");
  EXPECT_EQ(stats->rows[0][4], "-2.0000");
  EXPECT_EQ(stats->rows[0][5], "2.1602");
  EXPECT_EQ(stats->rows[0][6], "1.0000");
  EXPECT_EQ(stats->rows[2][4], "30.0100");
  std::string header;
  for (const auto& kv : d.header) header += kv.key + "=" + kv.value + ";";
  EXPECT_NE(header.find("model=m;"), std::string::npos) << header;
  EXPECT_NE(header.find("60 (the file has 360)"), std::string::npos) << header;
  EXPECT_NE(header.find("0.001000\""), std::string::npos) << header;
  // The model as the file states it: an .egm states no tide system, so a warning section says so.
  EXPECT_NE(header.find("model GM=398600441500000 m^3/s^2;model reference radius=6378136.3 m;"), std::string::npos)
      << header;
  EXPECT_NE(header.find("tide system=not stated by the file;normalisation=fully normalised (not stated"),
            std::string::npos)
      << header;
  const Section* warn = find_section(d, "warnings");
  ASSERT_NE(warn, nullptr);
  const auto* wn = std::get_if<Notes>(&warn->blocks.at(0));
  ASSERT_NE(wn, nullptr);
  ASSERT_EQ(wn->items.size(), 1u);
  EXPECT_NE(wn->items[0].find("does not state its tide system"), std::string::npos);
  // A model that states it has no warning section.
  EXPECT_EQ(find_section(gravity_points_document({"line.csv", kModel, track, s}), "warnings"), nullptr);
  // The sign convention is stated.
  const Section* def = find_section(d, "definitions");
  ASSERT_NE(def, nullptr);
  const auto* notes = std::get_if<Notes>(&def->blocks.at(0));
  ASSERT_NE(notes, nullptr);
  std::string all;
  for (const auto& i : notes->items) all += i;
  EXPECT_NE(all.find("astronomic minus geodetic"), std::string::npos);
  EXPECT_NE(all.find("xi = Phi - phi"), std::string::npos);
}

TEST(GravityPointsDocument, NoPointsNoMaps) {
  const Document d = gravity_points_document({"<stdin>", kModel, {}, gravity::PointsSummary()});
  EXPECT_EQ(find_section(d, "maps"), nullptr);
  EXPECT_TRUE(plots(d).empty());
  EXPECT_NE(find_section(d, "summary"), nullptr);
}

}  // namespace
