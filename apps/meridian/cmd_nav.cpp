// meridian nav inspect

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/io/nmea.hpp"
#include "meridian/report/nav_inspect.hpp"

namespace meridian::cli {
namespace nav_cmd {
namespace {

struct InspectArgs {
  std::vector<std::string> files;
  bool json = false, accept_missing_checksum = false;
};

int run_inspect(const InspectArgs& a) {
  io::nmea::Options o;
  o.accept_missing_checksum = a.accept_missing_checksum;
  // Every file is read before anything is printed: an unreadable one fails the whole run.
  std::vector<io::nmea::Summary> summaries;
  for (const std::string& f : a.files) summaries.push_back(io::nmea::read_file(f, o));
  std::string text;
  if (a.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& s : summaries) files.push_back(report::nav_inspect_to_json(s));
    text = nlohmann::json{{"files", files}}.dump(2) + "\n";
  } else {
    for (std::size_t k = 0; k < summaries.size(); ++k)
      text += (k ? "\n" : "") + report::nav_inspect_text(summaries[k]);
  }
  emit("", text);
  return kOk;
}

}  // namespace
}  // namespace nav_cmd

void add_nav_commands(CLI::App& app, int& exit_code) {
  using namespace nav_cmd;
  CLI::App* nav = app.add_subcommand("nav", "Marine navigation: inspect NMEA 0183 logs");
  nav->require_subcommand(1);
  auto ia = std::make_shared<InspectArgs>();
  CLI::App* ins = nav->add_subcommand(
      "inspect", "Count sentences and report bad, missing-checksum, duplicate and rolled-over ones per file");
  ins->add_option("FILE", ia->files, "NMEA 0183 log(s)")->required();
  ins->add_flag("--json", ia->json, "Print {\"files\": [one object per file]} as JSON");
  ins->add_flag("--accept-missing-checksum", ia->accept_missing_checksum,
                "Accept sentences without *HH (counted, with a warning)");
  ins->callback([ia, &exit_code] { exit_code = guarded([&] { return run_inspect(*ia); }); });
}

}  // namespace meridian::cli
