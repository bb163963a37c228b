#pragma once
// Test-only: runs the meridian binary (MERIDIAN_EXE) in a fresh temporary
// directory per test, capturing exit code, stdout and stderr.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace meridian_test {

struct CmdResult {
  int code = -1;
  std::string out, err;
};

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("meridian_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  /// `meridian ARGS`, run inside the test's directory with `stdin_text` as input.
  CmdResult run(const std::string& args, const std::string& stdin_text = "") {
    std::ofstream(dir_ / "stdin") << stdin_text;
    return shell("(" + std::string(MERIDIAN_EXE) + " " + args + ") < stdin");
  }
  /// Any command line (pipes allowed), run inside the test's directory.
  CmdResult shell(const std::string& cmdline) {
    const std::string cmd = "cd " + dir_.string() + " && (" + cmdline + ") > stdout 2> stderr";
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "stdout"), slurp(dir_ / "stderr")};
  }

  std::filesystem::path dir_;
};

}  // namespace meridian_test
