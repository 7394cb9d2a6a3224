// SPDX-License-Identifier: MIT
// The one writer (core/output_file.h): whole files replaced atomically, logs appended, and every
// failure an error that names the file and the system's real reason. Tests run as root, whom
// permissions do not stop: a path under a regular file (FILE/x), /proc and /dev/full fail for
// root too.
#include "sewerplan/core/output_file.h"

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "sewerplan/core/text_file.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sewerplan {
namespace {

namespace fs = std::filesystem;

class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewerplan_output_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // The directory's entries but `keep`: a failed write must leave no temporary file behind.
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }

  fs::path dir_;
};

TEST_F(OutputFile, WritesAndReplacesAWholeFile) {
  const fs::path p = dir_ / "map.json";
  ASSERT_TRUE(write_text_file(p, "first").has_value());
  EXPECT_EQ(slurp(p), "first");
  ASSERT_TRUE(write_text_file(p, "second, longer").has_value());
  EXPECT_EQ(slurp(p), "second, longer");
  EXPECT_EQ(entries(), 1U);  // no temporary file left
}

TEST_F(OutputFile, KeepsAnExistingFilesMode) {
  const fs::path p = dir_ / "script.sh";
  ASSERT_TRUE(write_text_file(p, "a").has_value());
  ::chmod(p.c_str(), 0750);
  ASSERT_TRUE(write_text_file(p, "b").has_value());
  struct stat st {};
  ASSERT_EQ(::stat(p.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0750U);
}

TEST_F(OutputFile, ADirectoryThatIsAFileFailsNamingTheFileAndTheReason) {
  const fs::path file = dir_ / "plain";
  ASSERT_TRUE(write_text_file(file, "x").has_value());
  const Result<void> w = write_text_file(file / "out.json", "y");
  ASSERT_FALSE(w.has_value());
  EXPECT_EQ(w.error().code, ErrorCode::kIo);
  EXPECT_EQ(w.error().message,
            "cannot write " + (file / "out.json").string() + ": Not a directory");
}

TEST_F(OutputFile, ADirectoryAsTheTargetIsRefusedAndKept) {
  fs::create_directories(dir_ / "out");
  const Result<void> w = write_text_file(dir_ / "out", "y");
  ASSERT_FALSE(w.has_value());
  EXPECT_EQ(w.error().message, "cannot write " + (dir_ / "out").string() + ": it is a directory");
  EXPECT_TRUE(fs::is_directory(dir_ / "out"));
  EXPECT_EQ(entries(), 1U);
}

TEST_F(OutputFile, AFullDeviceIsWrittenInPlaceAndItsFailureNamed) {
  // /dev/full is a character device: written directly (never a /dev/full.tmp renamed over it),
  // and its ENOSPC reported, not "Success".
  const Result<void> w = write_text_file("/dev/full", "anything");
  ASSERT_FALSE(w.has_value());
  EXPECT_EQ(w.error().message, "cannot write /dev/full: No space left on device");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST_F(OutputFile, ADeviceThatTakesTheTextIsWrittenInPlace) {
  EXPECT_TRUE(write_text_file("/dev/null", "gone").has_value());
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST_F(OutputFile, AFailedWriteLeavesTheOldFile) {
  // A read-only place even for root: /proc/self is a directory no file can be created in.
  const Result<void> w = write_text_file("/proc/self/sewerplan-out.json", "new");
  ASSERT_FALSE(w.has_value());
  EXPECT_NE(w.error().message.find("cannot write /proc/self/sewerplan-out.json: "),
            std::string::npos);
  EXPECT_EQ(w.error().message.find("Success"), std::string::npos) << w.error().message;
}

TEST_F(OutputFile, AWriteThatFailsHalfwayLeavesTheOldFileWhole) {
  // A disk that fills up halfway, for root too: a file size limit (the write fails with EFBIG
  // once the new text passes it; SIGXFSZ ignored so that the process lives to report it).
  const fs::path old = dir_ / "plan.txt";
  ASSERT_TRUE(write_text_file(old, "the old plan\n").has_value());
  rlimit before{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &before), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = before;
  small.rlim_cur = 64;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const Result<void> w = write_text_file(old, std::string(1000, 'n'));
  ::setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, previous);
  ASSERT_FALSE(w.has_value());
  EXPECT_EQ(w.error().message, "cannot write " + old.string() + ": File too large");
  EXPECT_EQ(slurp(old), "the old plan\n");
  EXPECT_EQ(entries(), 1U);  // the half-written temporary file is gone
}

TEST_F(OutputFile, ASymbolicLinkIsFollowedNotReplaced) {
  const fs::path target = dir_ / "target.txt";
  ASSERT_TRUE(write_text_file(target, "old").has_value());
  fs::create_symlink(target, dir_ / "link.txt");
  ASSERT_TRUE(write_text_file(dir_ / "link.txt", "new").has_value());
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.txt"));
  EXPECT_EQ(slurp(target), "new");
  // A link to a device is written in place too.
  fs::create_symlink("/dev/full", dir_ / "full");
  const Result<void> w = write_text_file(dir_ / "full", "x");
  ASSERT_FALSE(w.has_value());
  EXPECT_NE(w.error().message.find("No space left on device"), std::string::npos);
  EXPECT_TRUE(fs::is_symlink(dir_ / "full"));
}

TEST_F(OutputFile, ALogIsAppendedEventByEvent) {
  const fs::path p = dir_ / "events.jsonl";
  ASSERT_TRUE(write_text_file(p, "an older run\n").has_value());
  Result<LogFile> log = LogFile::open(p);
  ASSERT_TRUE(log.has_value()) << log.error().message;
  EXPECT_TRUE(log->append("one\n"));
  EXPECT_EQ(slurp(p), "one\n");  // on the disk at once, without a close
  EXPECT_TRUE(log->append("two\n"));
  EXPECT_EQ(slurp(p), "one\ntwo\n");
  EXPECT_TRUE(log->close().has_value());
  EXPECT_EQ(log->failed_appends(), 0U);
}

TEST_F(OutputFile, AFailingLogCountsItsLostWritesAndSaysWhy) {
  Result<LogFile> log = LogFile::open("/dev/full");
  ASSERT_TRUE(log.has_value()) << log.error().message;
  EXPECT_FALSE(log->append("one\n"));
  EXPECT_FALSE(log->append("two\n"));
  EXPECT_EQ(log->appends(), 2U);
  EXPECT_EQ(log->failed_appends(), 2U);
  ASSERT_TRUE(log->first_error().has_value());
  EXPECT_EQ(*log->first_error(), "cannot write /dev/full: No space left on device");
  const Result<void> closed = log->close();
  ASSERT_FALSE(closed.has_value());
  EXPECT_EQ(closed.error().message,
            "cannot write /dev/full: No space left on device (2 of 2 writes lost)");
}

TEST_F(OutputFile, ALogThatCannotBeOpenedNamesItself) {
  const fs::path file = dir_ / "plain";
  ASSERT_TRUE(write_text_file(file, "x").has_value());
  const Result<LogFile> under_file = LogFile::open(file / "events.jsonl");
  ASSERT_FALSE(under_file.has_value());
  EXPECT_EQ(under_file.error().message,
            "cannot write " + (file / "events.jsonl").string() + ": Not a directory");
  const Result<LogFile> dir = LogFile::open(dir_);
  ASSERT_FALSE(dir.has_value());
  EXPECT_EQ(dir.error().message, "cannot write " + dir_.string() + ": it is a directory");
}

// Inputs that are not regular files: a FIFO nobody writes to must not block, a device that never
// ends is refused, a directory named.
TEST_F(OutputFile, ReadingAFifoWithoutWriterDoesNotBlock) {
  const fs::path fifo = dir_ / "map.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const Result<std::string> text = read_text_file(fifo);
  ASSERT_FALSE(text.has_value());
  EXPECT_EQ(text.error().message, "cannot read " + fifo.string() +
                                      ": it is a FIFO (named pipe) and nothing was written to it");
}

TEST_F(OutputFile, ReadingADeviceIsRefused) {
  const Result<std::string> zero = read_text_file("/dev/zero");
  ASSERT_FALSE(zero.has_value());
  EXPECT_EQ(zero.error().message, "cannot read /dev/zero: it is a character device, not a file");
  const Result<std::string> dir = read_text_file(dir_);
  ASSERT_FALSE(dir.has_value());
  EXPECT_EQ(dir.error().message, "cannot read " + dir_.string() + ": it is a directory");
}

TEST_F(OutputFile, ReadingAPipeWithAWriterReadsItWhole) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const std::string text(200'000, 'x');  // more than a pipe holds: read while it is written
  std::thread writer([&] {
    std::string_view rest = text;
    while (!rest.empty()) {
      const ssize_t n = ::write(fds[1], rest.data(), rest.size());
      if (n <= 0) break;
      rest.remove_prefix(static_cast<std::size_t>(n));
    }
    ::close(fds[1]);
  });
  const Result<std::string> got = read_text_file("/proc/self/fd/" + std::to_string(fds[0]));
  writer.join();
  ::close(fds[0]);
  ASSERT_TRUE(got.has_value()) << got.error().message;
  EXPECT_EQ(*got, text);
}

}  // namespace
}  // namespace sewerplan
