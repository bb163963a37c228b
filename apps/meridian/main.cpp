// meridian: the command-line tool. It only parses arguments, calls the
// library and formats results; see docs/cli.md.

#include <CLI/CLI.hpp>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/version.hpp"


int main(int argc, char** argv) {
  CLI::App app{"meridian - true north and the plumb line from instrument data"};
  app.set_version_flag("--version", std::string("meridian ") + meridian::version());
  app.require_subcommand(1);
  int exit_code = meridian::cli::kOk;
  meridian::cli::add_gyro_commands(app, exit_code);
  meridian::cli::add_gravity_commands(app, exit_code);
  meridian::cli::add_demo_command(app, exit_code);
  meridian::cli::add_report_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return meridian::cli::kUsage;
  }
  return exit_code;
}
