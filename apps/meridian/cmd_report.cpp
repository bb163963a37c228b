// meridian report pdf | screenshot: print an HTML report with a headless
// Chromium (Debian's `chromium`), which runs the inlined plotting code first.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli_support.hpp"
#include "commands.hpp"
#include "meridian/core/error.hpp"

extern char** environ;

namespace meridian::cli {
namespace report_cmd {
namespace {

namespace fs = std::filesystem;

// MERIDIAN_CHROMIUM, else the first of the usual names on PATH.
std::string find_chromium() {
  if (const char* c = std::getenv("MERIDIAN_CHROMIUM"); c && *c) return c;
  const char* path = std::getenv("PATH");
  std::string p = path ? path : "/usr/bin:/bin";
  for (const char* name : {"chromium", "chromium-browser", "google-chrome", "google-chrome-stable"}) {
    std::size_t start = 0;
    while (start <= p.size()) {
      const std::size_t end = p.find(':', start);
      const fs::path candidate = fs::path(p.substr(start, end - start)) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  throw IoError("no Chromium found: install Debian's chromium package (apt-get install chromium) "
                "or set MERIDIAN_CHROMIUM to the browser's path");
}

// Run the browser on `html` with `action` ("--print-to-pdf=…" or
// "--screenshot=…"); its chatter goes to /dev/null.
void run_chromium(const fs::path& html, const std::string& action, const std::vector<std::string>& extra) {
  const std::string chromium = find_chromium();
  char tmpl[] = "/tmp/meridian-chromium-XXXXXX";
  if (!::mkdtemp(tmpl)) throw IoError("cannot create a temporary browser profile directory");
  const std::string profile = tmpl;
  std::vector<std::string> args{chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                                "--disable-quic", "--user-data-dir=" + profile, "--virtual-time-budget=20000",
                                "--run-all-compositor-stages-before-draw"};
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back(action);
  args.push_back("file://" + fs::absolute(html).string());
  std::vector<char*> argv;
  for (auto& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, chromium.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  int status = 0;
  if (rc == 0) ::waitpid(pid, &status, 0);
  std::error_code ec;
  fs::remove_all(profile, ec);
  if (rc != 0) throw IoError(fmt::format("cannot start {}", chromium));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw IoError(fmt::format("{} failed on {}", chromium, html.string()));
}

struct PrintArgs {
  std::string html, output;
  int width_px = 1000, height_px = 2400;
};

// Print to a temporary file beside the target, then rename: atomic.
void print_atomically(const PrintArgs& a, const char* ext, const std::string& flag,
                      const std::vector<std::string>& extra) {
  if (!fs::exists(a.html)) throw IoError("no such file", {a.html, std::nullopt, {}});
  const fs::path out = a.output.empty() ? fs::path(a.html).replace_extension(ext) : fs::path(a.output);
  const fs::path tmp = out.parent_path() / ("." + out.filename().string() + ".tmp" + ext);
  run_chromium(a.html, flag + fs::absolute(tmp).string(), extra);
  if (!fs::exists(tmp) || fs::file_size(tmp) == 0)
    throw IoError("the browser wrote nothing", {out.string(), std::nullopt, {}});
  fs::rename(tmp, out);
  std::printf("%s\n", out.string().c_str());
}

}  // namespace
}  // namespace report_cmd

void add_report_commands(CLI::App& app, int& exit_code) {
  using namespace report_cmd;  // the command's option structs and run functions
  CLI::App* rep = app.add_subcommand("report", "Print HTML reports (needs Debian's chromium)");
  rep->require_subcommand(1);
  auto pa = std::make_shared<PrintArgs>();
  CLI::App* pdf = rep->add_subcommand("pdf", "Print an HTML report to an A4 PDF");
  pdf->add_option("HTML", pa->html, "The report (from --report or meridian demo)")->required();
  pdf->add_option("-o,--output", pa->output, "PDF file (default: the HTML name with .pdf)");
  pdf->callback([pa, &exit_code] {
    exit_code = guarded([&] {
      print_atomically(*pa, ".pdf", "--print-to-pdf=", {"--no-pdf-header-footer", "--print-to-pdf-no-header"});
      return kOk;
    });
  });
  auto sa = std::make_shared<PrintArgs>();
  CLI::App* shot = rep->add_subcommand("screenshot", "Render an HTML report to a PNG picture");
  shot->add_option("HTML", sa->html, "The report")->required();
  shot->add_option("-o,--output", sa->output, "PNG file (default: the HTML name with .png)");
  shot->add_option("--width", sa->width_px, "Window width (px)")->capture_default_str();
  shot->add_option("--height", sa->height_px, "Window height (px)")->capture_default_str();
  shot->callback([sa, &exit_code] {
    exit_code = guarded([&] {
      print_atomically(*sa, ".png", "--screenshot=",
                       {"--hide-scrollbars", fmt::format("--window-size={},{}", sa->width_px, sa->height_px)});
      return kOk;
    });
  });
}

}  // namespace meridian::cli
