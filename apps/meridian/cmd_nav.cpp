// meridian nav inspect | simulate | process

#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/error.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/io/nmea.hpp"
#include "meridian/nav/simulator.hpp"
#include "meridian/report/html.hpp"
#include "meridian/report/json_text.hpp"
#include "meridian/report/nav_html.hpp"
#include "meridian/report/nav_inspect.hpp"
#include "meridian/report/nav_outputs.hpp"

namespace meridian::cli {
namespace nav_cmd {
namespace {

struct InspectArgs {
  std::vector<std::string> files;
  bool json = false, accept_missing_checksum = false;
};

int run_inspect(const InspectArgs& a) {
  // Every file is read before anything is printed: an unreadable one fails the whole run.
  const std::vector<nav::LogInspection> summaries = io::nmea::inspect_files(a.files, a.accept_missing_checksum);
  emit("", a.json ? report::json_text(report::nav_inspect_files_to_json(summaries)) : report::nav_inspect_text(summaries));
  return kOk;
}

struct SimulateArgs {
  std::string scenario = "A";
  std::int64_t seed = 1;  // ≥ 0 (checked): an unsigned option would wrap -1 silently
  std::string out;
  int stations = 3;
  double duration_s = 1800.0;
  double fixes_every_s = 0.0;
};

int run_simulate(const SimulateArgs& a) {
  nav::SimulationOptions so;
  so.scenario = nav::scenario_from_string(a.scenario);
  so.seed = static_cast<std::uint64_t>(a.seed);
  so.stations = a.stations;
  so.duration_s = a.duration_s;
  so.fix_interval_s = a.fixes_every_s;
  io::write_nav_simulation(a.out, nav::simulate(so), so);
  return kOk;
}

struct ProcessArgs {
  std::string config, track, geojson, rejected, report;
  std::string method = "rts";
  bool json = false, quiet = false, force = false;
};


// What the options ask of the result: the -o method computed, a projection for --geojson.
void check_result_for(const ProcessArgs& a, nav::Method method, const nav::Result& r) {
  if (!a.track.empty() && !r.find(method))
    throw InputError(fmt::format("the method {} was not computed for this job{}", a.method,
                                 method == nav::Method::FixClosure ? " (it needs fixes)" : ""),
                     {"", std::nullopt, "--method"});
  // A method whose self-checks failed (diverged, inconsistent) is not exported without --force:
  // its track may be far off while its σ look fine (issue 32).
  if (const nav::MethodResult* m = r.find(method); !a.track.empty() && m && !m->consistency.sigma_valid() && !a.force) {
    const nav::ConsistencyAlarm& al = m->consistency.alarms.front();
    throw InputError(fmt::format("the method {} is marked {} by its self-checks ({} from {:.1f} s to {:.1f} s: {}); "
                                 "its track and σ are not valid there: choose a consistent method with --method, "
                                 "or export it anyway with --force",
                                 a.method, nav::to_string(m->consistency.status), al.check, al.from_s, al.to_s,
                                 al.reason),
                     {"", std::nullopt, "--method"});
  }
  if (!a.geojson.empty() && !r.projection)
    throw InputError("GeoJSON needs latitudes and longitudes: the job is in plane coordinates without a "
                     "projection (give projection: in the configuration)",
                     {"", std::nullopt, "--geojson"});
}

int run_process(const ProcessArgs& a) {
  require_html_reports_for(a.report);
  const nav::Method method = nav::method_from_string(a.method);
  const io::NavConfig config = io::read_nav_config(a.config);
  check_output_paths({{a.track, "-o", "track"},
                      {a.geojson, "--geojson", "GeoJSON track"},
                      {a.rejected, "--rejected", "list of rejected observations"},
                      {a.report, "--report", "report"}},
                     io::nav_input_files(config));
  TerminalProgress progress(a.quiet);
  const nav::Result r = io::run_nav(config, &progress).result;
  check_result_for(a, method, r);
  // Everything is computed before anything is written (atomic outputs).
  const std::string text = a.json ? report::json_text(report::nav_to_json(r)) : report::nav_summary_text(r);
  const std::string track = a.track.empty() ? std::string() : report::nav_track_csv(r, method);
  const std::string geojson = a.geojson.empty() ? std::string() : report::nav_track_geojson(r, {});
  const std::string rejected = a.rejected.empty() ? std::string() : report::nav_rejected_csv(r);
  const std::string html =
      a.report.empty() ? std::string() : report::render_html(report::nav_document(r, "Marine navigation: " + a.config));
  emit_all({{a.track, track}, {a.geojson, geojson}, {a.rejected, rejected}, {a.report, html},
            {kStandardOutput, text}});
  return kOk;
}

void add_inspect(CLI::App* nav, int& exit_code) {
  auto ia = std::make_shared<InspectArgs>();
  CLI::App* ins = nav->add_subcommand(
      "inspect", "Count sentences and report bad, missing-checksum, duplicate and rolled-over ones per file");
  ins->add_option("FILE", ia->files, "NMEA 0183 log(s)")->required();
  ins->add_flag("--json", ia->json, "Print {\"files\": [one object per file]} as JSON");
  ins->add_flag("--accept-missing-checksum", ia->accept_missing_checksum,
                "Accept sentences without *HH (counted, with a warning)");
  ins->callback([ia, &exit_code] { exit_code = guarded([&] { return run_inspect(*ia); }); });
}

void add_simulate(CLI::App* nav, int& exit_code) {
  auto sa = std::make_shared<SimulateArgs>();
  CLI::App* sim = nav->add_subcommand(
      "simulate", "Simulate the 1988 validation line (spec section 8): DR, stations, LOPs, truth, fixes, nav.yaml");
  sim->add_option("--scenario", sa->scenario, "A bias, B no bias, C bias change, D bad start")
      ->check(CLI::IsMember({"A", "B", "C", "D", "a", "b", "c", "d"}))
      ->capture_default_str();
  sim->add_option("--seed", sa->seed, "Random seed (>= 0)")
      ->check(CLI::Validator(
          [](const std::string& v) {
            std::int64_t n = 0;
            return CLI::detail::lexical_cast(v, n) && n >= 0
                       ? std::string()
                       : fmt::format("must be an integer >= 0, not {}", v);
          },
          "INTEGER >= 0"))
      ->capture_default_str();
  sim->add_option("--out", sa->out, "Directory to write (created when missing)")->required();
  sim->add_option("--stations", sa->stations, "Shore stations (2 or 3)")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  sim->add_option("--duration-s", sa->duration_s, "Length of the line (s; at least one DR step, 5 s)")
      ->check(CLI::Validator(
          [](const std::string& v) {
            double d = 0.0;
            if (!CLI::detail::lexical_cast(v, d) || !(d >= nav::SimulationOptions{}.step_s))
              return fmt::format("must be a number of seconds >= {:g} (one DR step: a line needs 2 DR "
                                 "samples), not {}",
                                 nav::SimulationOptions{}.step_s, v);
            return std::string();
          },
          "SECONDS >= 5"))
      ->capture_default_str();
  sim->add_option("--fixes-every-s", sa->fixes_every_s, "A satellite fix every this many seconds (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sim->callback([sa, &exit_code] { exit_code = guarded([&] { return run_simulate(*sa); }); });
}

void add_process(CLI::App* nav, int& exit_code) {
  auto pa = std::make_shared<ProcessArgs>();
  CLI::App* pro = nav->add_subcommand(
      "process", "Dead reckoning + LOPs + fixes: the sequential adjustment, its variants, EKF and RTS smoother");
  pro->add_option("CONFIG", pa->config, "YAML or JSON configuration (docs/file-formats.md)")->required();
  pro->add_flag("--json", pa->json, "Print the summary as JSON");
  pro->add_option("-o,--output", pa->track, "Write the track CSV of --method here");
  pro->add_option("--method", pa->method,
                  "Method of the -o track: dead-reckoning, sequential-no-bias, sequential-bias-I, "
                  "sequential-bias-II, backward, fix-closure, ekf, rts")
      ->capture_default_str();
  pro->add_flag("--force", pa->force,
                "Write the -o track even when --method is marked diverged or inconsistent by its self-checks");
  pro->add_option("--geojson", pa->geojson, "Write the tracks of every method as GeoJSON (needs a projection)");
  pro->add_option("--rejected", pa->rejected, "Write the rejected observations as CSV");
  pro->add_option("--report", pa->report, "Write an HTML report");
  pro->add_flag("-q,--quiet", pa->quiet, "No progress bar");
  pro->callback([pa, &exit_code] { exit_code = guarded([&] { return run_process(*pa); }); });
}


}  // namespace
}  // namespace nav_cmd

void add_nav_commands(CLI::App& app, int& exit_code) {
  CLI::App* nav = app.add_subcommand(
      "nav", "Marine navigation: inspect NMEA 0183 logs, simulate and process survey lines");
  nav->require_subcommand(1);
  nav_cmd::add_inspect(nav, exit_code);
  nav_cmd::add_simulate(nav, exit_code);
  nav_cmd::add_process(nav, exit_code);
}

}  // namespace meridian::cli
