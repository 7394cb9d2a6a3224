// SPDX-License-Identifier: MIT
// The one way sewerplan writes files: whole files replaced atomically, and logs appended event by
// event, every write and close checked, every failure an error naming the file and the system's
// reason ("cannot write out.json: No space left on device").
//
// A whole file (a map, a plan, a picture, a campaign summary) is written to a temporary file in
// the same directory, synced to the disk, and renamed over the target: a crash or a full disk
// leaves the old file or the new one, never half of one. A target that is not a regular file (a
// device such as /dev/stdout or /dev/full, a FIFO) is written directly, never renamed over; a
// directory is refused. A symbolic link is followed: the file it points to is replaced.
//
// A log (the event log of a mission, a CAN log) is opened once, truncated, and appended to as the
// mission goes: each append is one write(2) of whole lines, so a crash leaves every event logged
// before it. A failed append does not stop the caller (a robot must not stop in a pipe because a
// log could not be written): it is counted, the first failure is kept, and later appends are
// still tried (a disk may have room again).
//
//   if (Result<void> w = write_text_file("plan.txt", text); !w.has_value()) ...  // exit 3
//   Result<LogFile> log = LogFile::open("events.jsonl");
//   log->append(line);  // false on failure; log->first_error() says why
//
// Thread safety: the functions share nothing. A LogFile is used by one thread at a time.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"

namespace sewerplan {

// Writes `text` as the whole content of `path` (see above). Errors are kIo and name `path`.
Result<void> write_text_file(const std::filesystem::path& path, std::string_view text);

// Makes `dir` (and its parents) a directory to write files into, if it is not one yet. kIo naming
// `dir` and the reason if it cannot be made or is something else (a file).
Result<void> create_output_directory(const std::filesystem::path& dir);

// A file written as a log: truncated at open, then appended to.
class LogFile {
 public:
  // Creates or truncates `path` (a device or FIFO is opened for writing as it is). kIo if it
  // cannot be opened (a directory, a missing or read-only directory).
  static Result<LogFile> open(const std::filesystem::path& path);

  LogFile(LogFile&& other) noexcept;
  LogFile& operator=(LogFile&& other) noexcept;
  LogFile(const LogFile&) = delete;
  LogFile& operator=(const LogFile&) = delete;
  ~LogFile();  // closes; call close() to see whether that worked

  // Writes `text` at the end of the file (retrying short writes and interrupted calls). False if
  // it could not be written whole; then failed_appends() counts it and first_error() says why.
  bool append(std::string_view text);
  // Closes the file; an error if the close failed or any append failed (the first failure, and
  // how many appends were lost). Idempotent.
  Result<void> close();

  const std::string& path() const { return path_; }
  std::size_t appends() const { return appends_; }
  std::size_t failed_appends() const { return failed_; }
  // "cannot write events.jsonl: No space left on device", or nothing if every append worked.
  const std::optional<std::string>& first_error() const { return first_error_; }

 private:
  LogFile(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  void record(int error, bool lost_write = true);
  int fd_ = -1;
  std::string path_;
  std::size_t appends_ = 0;
  std::size_t failed_ = 0;
  std::optional<std::string> first_error_;
};

}  // namespace sewerplan
