// meridian demo: the main job on the bundled example data.

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/io/gyro_jobs.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/report/dov_html.hpp"
#include "meridian/report/dov_outputs.hpp"
#include "meridian/report/gyro_html.hpp"
#include "meridian/report/gyro_json.hpp"
#include "meridian/report/gyro_text.hpp"
#include "meridian/report/json_text.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/json_text.hpp"
#include "meridian/report/nav_html.hpp"
#include "meridian/report/nav_outputs.hpp"

namespace meridian::cli {
namespace demo_cmd {
namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  std::string examples_dir;
  // Outside any source tree by default, so running the tour writes nothing into the repository.
  std::string output_dir = (std::filesystem::temp_directory_path() / "meridian-demo").string();
};

// The examples bundled with the source tree, or installed beside the binary.
fs::path find_examples(const std::string& given) {
  if (!given.empty()) return given;
  for (const char* d : {MERIDIAN_SOURCE_EXAMPLES_DIR, MERIDIAN_INSTALLED_EXAMPLES_DIR})
    if (fs::exists(fs::path(d) / "campaign.yaml")) return d;
  throw IoError("cannot find the bundled examples; pass --examples DIR");
}

// The navigation examples: spec §8 scenario C (simulated, bundled) and, when the real logs are
// beside the project (../shared/data/nmea), the NBP1406 line. Text summaries to stdout, reports
// (and the JSON summaries) to `out`.
void run_navigation(const fs::path& dir, const fs::path& out, std::vector<fs::path>& written) {
  struct Job {
    const char* config;
    const char* name;
    const char* title;
  };
  for (const Job& j : {Job{"nav-scenario-c/nav.yaml", "nav-scenario-c",
                           "Marine navigation: spec scenario C (the DR bias changes at minutes 10 and 15)"},
                       Job{"nav-nbp1406.yaml", "nav-nbp1406",
                           "Marine navigation: R/V N. B. Palmer, NBP1406 (real logs)"}}) {
    const fs::path file = dir / j.config;
    if (!fs::exists(file)) continue;
    const io::NavConfig c = io::read_nav_config(file.string());
    if (c.nmea && !fs::exists(c.nmea->heading_path)) {
      std::cout << "\nmeridian demo: " << file.string() << " skipped: " << c.nmea->heading_path
                << " is not there (the real logs of ../shared/data/nmea)\n";
      continue;
    }
    const nav::Result r = io::run_nav(c).result;
    std::cout << "\nmeridian demo: " << j.title << " (" << file.string() << ")\n\n" << report::nav_summary_text(r);
    written.push_back(out / (std::string(j.name) + ".json"));
    emit(written.back().string(), report::json_text(report::nav_to_json(r)));
    if (report::html_reports_available()) {
      written.push_back(out / (std::string(j.name) + ".html"));
      emit(written.back().string(), report::render_html(report::nav_document(r, j.title)));
    }
  }
}

// Dynamic deflection of the vertical: a simulated half-hour line (spec §7, 1 Hz, 1801 epochs,
// typical errors and an initial LGU error), filtered and smoothed with the spec's defaults. The
// line is made in memory, as `meridian dov simulate --hours 0.5 --seed 4 --phi-e-arcsec 1.5
// --phi-n-arcsec -2 --phi-u-arcsec 4` writes it; text summary to stdout, JSON and report to `out`.
void run_deflection(const fs::path& out, std::vector<fs::path>& written) {
  dov::SimulationOptions so;
  so.duration_s = 0.5 * 3600.0;
  so.seed = 4;
  so.initial_attitude_error_rad = Eigen::Vector3d(1.5, -2.0, 4.0) * units::kArcsecond;
  const std::string title = "simulated half-hour line (dov simulate --hours 0.5 --seed 4 "
                            "--phi-e-arcsec 1.5 --phi-n-arcsec -2 --phi-u-arcsec 4)";
  dov::Input in = dov::simulate(so);
  in.origin = {title, "made in memory by the simulator, not written", {}};
  const dov::Result r = dov::process(in);
  std::cout << "\nmeridian demo: dynamic deflection of the vertical, " << title << "\n\n"
            << report::dov_summary_text(r);
  written.push_back(out / "dov-demo.json");
  emit(written.back().string(), report::json_text(report::dov_summary_to_json(r)));
  if (report::html_reports_available()) {
    written.push_back(out / "dov-demo.html");
    emit(written.back().string(), report::render_html(report::dov_document(r)));
  }
}

int run_demo(const DemoArgs& a) {
  const fs::path dir = find_examples(a.examples_dir);
  const fs::path file = dir / "campaign.yaml";
  const io::CampaignJob job = io::run_campaign_file(file);
  const gyro::CampaignResult& r = job.result;
  const std::string text = report::campaign_text(r, report::AngleFormat(r.input.angle_unit));
  std::cout << "meridian demo: gyro orientation campaign " << file.string() << "\n\n" << text;
  std::error_code ec;
  fs::create_directories(a.output_dir, ec);
  if (ec) throw IoError("cannot create the output directory: " + ec.message(), {a.output_dir, std::nullopt, {}});
  const fs::path out = a.output_dir;
  std::vector<fs::path> written{out / "campaign.txt", out / "campaign.json"};
  emit(written[0].string(), text);
  emit(written[1].string(), report::json_text(report::campaign_to_json(r)));
  if (!report::html_reports_available()) {
    std::cout << "\nNo HTML reports: " << report::html_reports_unavailable_message() << ".\n";
  } else {
    written.push_back(out / "campaign.html");
    emit(written.back().string(),
         report::render_html(report::gyro_campaign_document(r)));
    // Every reduction method side by side on the spec's example, and a tracking run.
    for (const char* name : {"spec-scenario-2", "tracking"}) {
      const io::ReduceJob g = io::run_reduce_file(dir / (std::string(name) + ".yaml"));
      written.push_back(out / (std::string(name) + ".html"));
      emit(written.back().string(),
           report::render_html(report::gyro_reduce_document(g.result)));
    }
  }
  run_navigation(dir, out, written);
  run_deflection(out, written);
  std::cout << "\nReports written:\n";
  for (const auto& p : written) std::cout << "  " << p.string() << "\n";
  if (report::html_reports_available())
    std::cout << "Open the .html files in a browser (they work offline); print them to PDF with\n"
                 "  meridian report pdf " << written[2].string() << "\n";
  return kOk;
}

}  // namespace
}  // namespace demo_cmd

void add_demo_command(CLI::App& app, int& exit_code) {
  using namespace demo_cmd;  // the command's option structs and run functions
  auto a = std::make_shared<DemoArgs>();
  CLI::App* demo = app.add_subcommand("demo", "Run the gyro campaign, the navigation examples and a simulated deflection-of-the-vertical line");
  demo->add_option("--examples", a->examples_dir, "Directory of the example files");
  demo->add_option("--output-dir", a->output_dir, "Where the reports are written")->capture_default_str();
  demo->callback([a, &exit_code] { exit_code = guarded([&] { return run_demo(*a); }); });
}

}  // namespace meridian::cli
