// The HTML document renderer and the gyro report mapping.

#include <regex>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/report/gyro_html.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/web_assets.hpp"

using namespace meridian;
using namespace meridian::report;

namespace {
int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + what.size())) ++n;
  return n;
}
}  // namespace

TEST(Html, EscapesTextAndKeepsScriptsClosed) {
  EXPECT_EQ(html_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
  Document d;
  d.title = "T <x>";
  Plot p{"p", {{"data", {{"values", nlohmann::json::array({{{"label", "</script><b>"}}})}}}, {"mark", "point"}}, ""};
  d.sections.push_back(Section{"s1", "Section & one", {Paragraph{"<i>text</i>"}, p}, 2});
  const std::string html = render_html(d);
  EXPECT_NE(html.find("<title>T &lt;x&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("&lt;i&gt;text&lt;/i&gt;"), std::string::npos);
  // The spec's "</script>" must not end the JSON script element early.
  EXPECT_EQ(html.find("\"</script><b>\""), std::string::npos);
  EXPECT_NE(html.find("<\\/script>"), std::string::npos);
  EXPECT_NE(html.find("<section id=\"s1\">"), std::string::npos);
  EXPECT_EQ(count(html, "data-vega-spec="), 1);
}

TEST(Html, InlinesTheVegaLibrariesAndNeedsNoNetwork) {
  const WebAssets& a = web_assets();
  EXPECT_GT(a.vega_js.size(), 100000u);
  EXPECT_GT(a.vega_lite_js.size(), 50000u);
  EXPECT_GT(a.vega_embed_js.size(), 10000u);
  EXPECT_NE(a.vega_embed_js.find("vegaEmbed"), std::string_view::npos);
  EXPECT_NE(std::string(a.versions).find("vega-lite"), std::string::npos);
  const std::string html = render_html(Document{"t", "", {}, {}, "f"});
  EXPECT_FALSE(std::regex_search(html, std::regex("<script[^>]+src=")));
  EXPECT_NE(html.find("@page { size: A4"), std::string::npos);
  EXPECT_NE(html.find("data-render-status"), std::string::npos);
}

TEST(Html, CampaignDocumentHasEverySection) {
  const auto sim = gyro::simulate_campaign(gyro::example_campaign_truth(), 4);
  const auto r = gyro::process(sim.input);
  const Document d = gyro_campaign_document(r);
  std::vector<std::string> ids;
  for (const auto& s : d.sections) ids.push_back(s.id);
  for (const char* id : {"result", "checks", "calibration", "line", "known-before-1", "known-after-2",
                         "line-determination-1", "line-determination-3", "notes"})
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  const std::string html = render_html(d);
  // Per determination: its observations with the model, the residuals of a
  // fit with redundancy, every method side by side (method "all") and the
  // motor-off runs; plus the E and A_G spread plots.
  int expected = 2;
  auto add = [&](const std::vector<gyro::DeterminationInput>& in, const std::vector<gyro::DeterminationResult>& res) {
    ASSERT_EQ(in.size(), res.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      ++expected;
      const auto& p = res[i].primary;
      bool fitted = p.fit.has_value() || (p.reversal && p.reversal->dof > 0);
      for (const auto& m : res[i].all) fitted = fitted || m.fit.has_value();
      if (fitted) ++expected;
      if (res[i].all.size() > 1) ++expected;
      if (in[i].zero_before || in[i].zero_after) ++expected;
    }
  };
  add(sim.input.known_line->before, r.known_before);
  add(sim.input.known_line->after, r.known_after);
  add(sim.input.line.determinations, r.determinations);
  EXPECT_GE(expected, 10);
  EXPECT_EQ(count(html, "data-vega-spec="), expected);
  EXPECT_NE(html.find("Grid azimuth"), std::string::npos);
  EXPECT_NE(html.find("PASS"), std::string::npos);
}

TEST(Html, ResultSheetComesFirstAndTurnsRedOnAFailedCheck) {
  auto sim = gyro::simulate_campaign(gyro::example_campaign_truth(), 4);
  sim.input.record.observer = "王工";
  sim.input.record.checked_by = "陈工";
  const auto good = gyro::process(sim.input);
  const Document d = gyro_campaign_document(good);
  ASSERT_FALSE(d.sections.empty());
  const Section& sheet = d.sections.front();
  EXPECT_EQ(sheet.id, "result-sheet");
  EXPECT_TRUE(sheet.page_break_after);
  const auto* box = std::get_if<Highlight>(&sheet.blocks.front());
  ASSERT_NE(box, nullptr);
  EXPECT_FALSE(box->alarm);
  bool signatures = false;
  for (const auto& b : sheet.blocks)
    if (const auto* s = std::get_if<Signatures>(&b)) {
      signatures = true;
      ASSERT_EQ(s->people.size(), 4u);
      EXPECT_EQ(s->people[0].value, "王工");
      EXPECT_EQ(s->people[3].value, "陈工");
    }
  EXPECT_TRUE(signatures);
  // One run on the line 2' off: the line's check fails and the box says so.
  sim.input.line.determinations[0].target_reading_rad->value += 120 * units::kArcsecond;
  const auto bad = gyro::process(sim.input);
  ASSERT_FALSE(bad.all_checks_pass());
  const Document d2 = gyro_campaign_document(bad);
  const auto* red = std::get_if<Highlight>(&d2.sections.front().blocks.front());
  ASSERT_NE(red, nullptr);
  EXPECT_TRUE(red->alarm);
  EXPECT_NE(red->detail.find("CHECKS FAILED"), std::string::npos) << red->detail;
  const std::string html = render_html(d2);
  EXPECT_NE(html.find("class=\"highlight alarm\""), std::string::npos);
  EXPECT_NE(html.find("class=\"page-break\""), std::string::npos);
  EXPECT_NE(html.find("counter(pages)"), std::string::npos);
}

// Page 1 holds gyro minus traverse and the warnings; a five-transit run shows the dt a checker
// recomputes by hand ((-2 t1 + 3 t2 - 2 t3 + 3 t4 - 2 t5)/3, computed here from the times).
TEST(Html, ResultSheetHasGyroMinusTraverseAndFiveTransitsShowTheirDt) {
  auto sim = gyro::simulate_campaign(gyro::example_campaign_truth(), 4);
  sim.input.record.language = "zh";
  // One non-tracking run on the line timed over five transits: two more passages, a period on.
  std::vector<double>* times = nullptr;
  for (auto& d : sim.input.line.determinations)
    if (d.mode == gyro::Mode::NonTracking && !d.nontracking.crossings.empty()) {
      d.nontracking.crossings.resize(1);
      times = &d.nontracking.crossings[0].times_s;
      break;
    }
  ASSERT_NE(times, nullptr);
  ASSERT_EQ(times->size(), 3u);
  const double period = (*times)[2] - (*times)[0];
  times->push_back((*times)[1] + period);
  times->push_back((*times)[2] + period);
  const std::vector<double> t = *times;
  const auto r = gyro::process(sim.input);
  ASSERT_TRUE(r.line_grid_azimuth_from_coordinates_rad.has_value());
  const std::string html = render_html(gyro_campaign_document(r));
  const std::string sheet = html.substr(0, html.find("id=\"inputs\""));
  EXPECT_NE(sheet.find("陀螺方位角与导线方位角之差 gyro minus traverse azimuth"), std::string::npos);
  EXPECT_NE(sheet.find("坐标方位角 Grid azimuth"), std::string::npos);
  EXPECT_NE(sheet.find("已知边 Known line"), std::string::npos);
  // Its limit and verdict beside it, and the check table's headings in the sheet's language.
  EXPECT_NE(sheet.find("限差 limit \u00b140.0&quot; 合格 PASS"), std::string::npos);
  EXPECT_NE(html.find("<th>检核项目 check</th><th>实测值 value</th><th>限差 limit</th><th>结论 result</th>"),
            std::string::npos);
  EXPECT_NE(html.find("<th>姓名 name</th><th>签名 signature</th><th>日期 date</th>"), std::string::npos);
  const double dt = (-2 * t[0] + 3 * t[1] - 2 * t[2] + 3 * t[3] - 2 * t[4]) / 3.0;
  EXPECT_NE(html.find(fmt::format("- 2 t5)/3 = {:.2f} s", dt)), std::string::npos) << dt;
}
