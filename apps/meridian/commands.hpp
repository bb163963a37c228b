#pragma once
// Subcommand registration. Each function adds its subcommand(s) to the app
// and stores the exit code of the one that ran in `exit_code`.

#include <CLI/CLI.hpp>

namespace meridian::cli {

void add_gyro_commands(CLI::App& app, int& exit_code);
void add_gravity_commands(CLI::App& app, int& exit_code);
void add_demo_command(CLI::App& app, int& exit_code);
void add_report_commands(CLI::App& app, int& exit_code);
void add_maglev_commands(CLI::App& app, int& exit_code);
void add_dov_commands(CLI::App& app, int& exit_code);
void add_nav_commands(CLI::App& app, int& exit_code);

}  // namespace meridian::cli
