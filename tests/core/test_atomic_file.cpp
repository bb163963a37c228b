#include <unistd.h>

#include <filesystem>
#include <vector>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/interrupt_cleanup.hpp"
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

TEST(AtomicFile, StreamingWriterCommitsOrLeavesNothing) {
  fs::path dir = fs::temp_directory_path() / ("meridian_atomic_stream_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path f = dir / "out.csv";
  meridian::write_file_atomically(f, "old\n");
  {
    meridian::AtomicFileWriter w(f);
    w.write("a,b\n");
    w.write("1,2\n");
    // Destroyed without commit: an interrupted run.
  }
  std::ifstream in1(f);
  std::stringstream s1;
  s1 << in1.rdbuf();
  EXPECT_EQ(s1.str(), "old\n");
  {
    meridian::AtomicFileWriter w(f);
    w.write("a,b\n");
    w.write("1,2\n");
    w.commit();
  }
  std::ifstream in2(f);
  std::stringstream s2;
  s2 << in2.rdbuf();
  EXPECT_EQ(s2.str(), "a,b\n1,2\n");
  int n = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(dir)) ++n;
  EXPECT_EQ(n, 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, WriteAtPatchesWhatWasWrittenAndNothingBeyond) {
  fs::path dir = fs::temp_directory_path() / ("meridian_atomic_at_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path f = dir / "out.bin";
  {
    meridian::AtomicFileWriter w(f);
    w.write("count=????\n");
    w.write("rows\n");
    w.write_at(6, "0042");  // the header's count, known at the end
    EXPECT_THROW(w.write_at(14, "xyz"), meridian::IoError);  // past the 16 bytes written
    w.commit();
  }
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "count=0042\nrows\n");
  fs::remove_all(dir);
}

// The interrupt registry (core/interrupt_cleanup.hpp): an atomic writer's temporary file is
// registered while it exists and released by commit or by the destructor; a full table does not
// fail the writer.
TEST(InterruptCleanup, WritersRegisterTheirTemporaryFileUntilCommitOrDestruction) {
  const std::size_t before = meridian::registered_temporary_files();
  const auto dir = std::filesystem::temp_directory_path() / ("meridian_guard_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    meridian::AtomicFileWriter a(dir / "a.txt");
    EXPECT_EQ(meridian::registered_temporary_files(), before + 1);
    {
      meridian::AtomicFileWriter b(dir / "b.txt");
      EXPECT_EQ(meridian::registered_temporary_files(), before + 2);
    }
    EXPECT_EQ(meridian::registered_temporary_files(), before + 1);
    a.write("x");
    a.commit();
    EXPECT_EQ(meridian::registered_temporary_files(), before);
  }
  std::vector<meridian::TemporaryFileGuard> guards;
  for (std::size_t i = 0; i < meridian::kMaxTemporaryFiles + 3; ++i)
    guards.emplace_back((dir / ("g" + std::to_string(i))).string());
  EXPECT_EQ(meridian::registered_temporary_files(), meridian::kMaxTemporaryFiles);
  EXPECT_FALSE(guards.back().registered());
  meridian::TemporaryFileGuard moved = std::move(guards.front());
  EXPECT_TRUE(moved.registered());
  EXPECT_FALSE(guards.front().registered());
  guards.clear();
  EXPECT_EQ(meridian::registered_temporary_files(), before + 1);
  moved.release();
  EXPECT_EQ(meridian::registered_temporary_files(), before);
  EXPECT_FALSE(meridian::TemporaryFileGuard(std::string(5000, 'x')).registered());
  std::filesystem::remove_all(dir);
}
