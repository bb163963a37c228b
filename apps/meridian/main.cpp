// meridian: the command-line tool. It only parses arguments, calls the
// library and formats results; see docs/cli.md.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/interrupt_cleanup.hpp"
#include "meridian/core/version.hpp"

namespace {

// Optimal string alignment distance: insertions, deletions, substitutions
// and transpositions of neighbours each count one ("strcit" -> "strict": 1).
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// The candidate a mistyped `word` most likely meant: the nearest within a
// third of its length (at least one edit), else the only one it begins.
std::optional<std::string> nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_d = std::max<std::size_t>(1, word.size() / 3) + 1;
  for (const auto& c : candidates)
    if (const std::size_t d = edit_distance(word, c); d < best_d) best = c, best_d = d;
  if (best) return best;
  std::vector<std::string> prefixed;
  for (const auto& c : candidates)
    if (word.size() >= 2 && c.rfind(word, 0) == 0) prefixed.push_back(c);
  if (prefixed.size() == 1) return prefixed.front();
  return std::nullopt;
}

// A word of the command line that names no command or option.
struct Unknown {
  std::string word, kind, command;  // kind: "command" or "option"
  std::vector<std::string> candidates;
};

std::vector<const CLI::App*> subcommands_of(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App*) { return true; });
}

// Walk the arguments as CLI11 reads them, down the subcommands, to the first
// word that is neither a subcommand, an option of the command it follows,
// an option's value nor a positional argument.
std::optional<Unknown> first_unknown(const CLI::App& app, int argc, char** argv) {
  const CLI::App* cur = &app;
  std::string command = "meridian";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    const bool number = arg.size() > 1 && (std::isdigit(static_cast<unsigned char>(arg[1])) || arg[1] == '.');
    if (arg.size() > 1 && arg[0] == '-' && !number) {
      const bool is_long = arg.rfind("--", 0) == 0;
      const std::string name = is_long ? arg.substr(2, arg.find('=') - 2) : arg.substr(1, 1);
      const CLI::Option* found = nullptr;
      for (const CLI::Option* o : cur->get_options())
        if (is_long ? o->check_lname(name) : o->check_sname(name)) found = o;
      if (!found) {
        Unknown u{is_long ? "--" + name : arg.substr(0, 2), "option", command, {}};
        for (const CLI::Option* o : cur->get_options())
          for (const auto& l : o->get_lnames()) u.candidates.push_back("--" + l);
        return u;
      }
      const bool value_attached = is_long ? arg.find('=') != std::string::npos : arg.size() > 2;
      if (found->get_items_expected_min() > 0 && !value_attached) ++i;  // its value
      continue;
    }
    const auto subs = subcommands_of(*cur);
    const auto sub = std::find_if(subs.begin(), subs.end(), [&](const CLI::App* s) { return s->check_name(arg); });
    if (sub != subs.end()) {
      cur = *sub;
      command += " " + arg;
      continue;
    }
    const auto options = cur->get_options();
    const bool takes_positionals =
        std::any_of(options.begin(), options.end(), [](const CLI::Option* o) { return o->get_positional(); });
    if (!subs.empty() && !takes_positionals) {
      Unknown u{arg, "command", command, {}};
      for (const CLI::App* s : subs) u.candidates.push_back(s->get_name());
      return u;
    }
  }
  return std::nullopt;
}

// "meridian gyro: unknown command "campain"; did you mean `campaign`?"
void explain(const Unknown& u) {
  std::string line = fmt::format("{}: unknown {} \"{}\"", u.command, u.kind, u.word);
  if (const auto s = nearest(u.word, u.candidates))
    line += fmt::format("; did you mean `{}`?", *s);
  else if (u.kind == "command")
    line += fmt::format(" (commands: {})", fmt::join(u.candidates, ", "));
  std::cerr << line << "\nRun with --help for more information.\n";
}

}  // namespace

int main(int argc, char** argv) {
  // Ctrl-C or a kill removes the atomic writers' temporary files (core/interrupt_cleanup.hpp).
  meridian::install_interrupt_cleanup();
  CLI::App app{"meridian - true north and the plumb line from instrument data"};
  app.set_version_flag("--version", std::string("meridian ") + meridian::version());
  app.require_subcommand(1);
  int exit_code = meridian::cli::kOk;
  meridian::cli::add_gyro_commands(app, exit_code);
  meridian::cli::add_gravity_commands(app, exit_code);
  meridian::cli::add_maglev_commands(app, exit_code);
  meridian::cli::add_dov_commands(app, exit_code);
  meridian::cli::add_nav_commands(app, exit_code);
  meridian::cli::add_demo_command(app, exit_code);
  meridian::cli::add_report_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    const int rc = app.exit(e);  // --help, --version
    return meridian::cli::close_standard_output() ? rc : meridian::cli::kIoError;
  } catch (const CLI::ParseError& e) {
    if (const auto u = first_unknown(app, argc, argv))
      explain(*u);
    else
      app.exit(e);
    return meridian::cli::kUsage;
  }
  // Whatever a command wrote to standard output (std::cout or stdio) must have reached it.
  // (A command that failed has said why; its unwritten output need not be named twice.)
  if (exit_code == meridian::cli::kOk && !meridian::cli::close_standard_output()) return meridian::cli::kIoError;
  if (exit_code != meridian::cli::kOk) {
    // A failed run has cleaned up (its temporary files went with the stack) and said why; it
    // leaves without the libraries' exit handlers: libhdf5's closes files whose writes failed
    // (a disk that filled during a NetCDF write) and crashed doing so (issue 35).
    std::fflush(nullptr);
    std::_Exit(exit_code);
  }
  return exit_code;
}
