#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"

namespace fs = std::filesystem;

TEST(AtomicFile, WritesAndReplacesWithoutLeftovers) {
  fs::path dir = fs::temp_directory_path() / ("meridian_atomic_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::path f = dir / "out.txt";
  meridian::write_file_atomically(f, "first");
  meridian::write_file_atomically(f, "second\n");
  std::ifstream in(f);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "second\n");
  int n = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(dir)) ++n;
  EXPECT_EQ(n, 1);  // no temporary file left behind
  fs::remove_all(dir);
}

TEST(AtomicFile, MissingDirectoryThrowsIoError) {
  EXPECT_THROW(meridian::write_file_atomically("/nonexistent-dir-xyz/out.txt", "x"), meridian::IoError);
}
