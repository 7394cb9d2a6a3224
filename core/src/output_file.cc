// SPDX-License-Identifier: MIT
#include "sewerplan/core/output_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sewerplan {
namespace {

Error write_error(const std::filesystem::path& path, int error) {
  return Error{ErrorCode::kIo, "cannot write " + path.string() + ": " + std::strerror(error)};
}

// Writes all of `text` to `fd`; 0 or the errno of the failure. A write that makes no progress
// without an error (it should not happen) is reported as ENOSPC, never as "Success".
int write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return ENOSPC;
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return 0;
}

int open_errno(const char* path, int flags, mode_t mode, int& fd) {
  do {
    fd = ::open(path, flags | O_CLOEXEC, mode);
  } while (fd < 0 && errno == EINTR);
  return fd < 0 ? errno : 0;
}

// Writes `text` to an existing file that is not a regular file (a device, a FIFO) as it is.
Result<void> write_in_place(const std::filesystem::path& path, std::string_view text) {
  int fd = -1;
  if (int e = open_errno(path.c_str(), O_WRONLY, 0, fd); e != 0) return write_error(path, e);
  const int e = write_all(fd, text);
  const int closed = ::close(fd) == 0 ? 0 : errno;
  if (e != 0) return write_error(path, e);
  if (closed != 0 && closed != EINTR) return write_error(path, closed);
  return {};
}

std::atomic<unsigned> g_temporary_counter{0};

}  // namespace

Result<void> write_text_file(const std::filesystem::path& given, std::string_view text) {
  std::filesystem::path path = given;
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
    // Replace the file the link points to, not the link.
    std::error_code ec;
    std::filesystem::path target = std::filesystem::weakly_canonical(path, ec);
    if (!ec) path = std::move(target);
  }
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      return Error{ErrorCode::kIo, "cannot write " + given.string() + ": it is a directory"};
    }
    if (!S_ISREG(st.st_mode)) return write_in_place(given, text);
  }
  // A temporary file beside the target (a rename does not cross file systems), created with
  // O_EXCL so that two writers never share one.
  std::filesystem::path tmp;
  int fd = -1;
  for (int attempt = 0;; ++attempt) {
    tmp = path;
    tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(g_temporary_counter++);
    const int e = open_errno(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666, fd);
    if (e == 0) break;
    if (e != EEXIST || attempt > 100) return write_error(given, e);
  }
  if (S_ISREG(st.st_mode)) ::fchmod(fd, st.st_mode & 07777);  // keep an existing file's mode
  int e = write_all(fd, text);
  if (e == 0 && ::fsync(fd) != 0) e = errno;
  if (::close(fd) != 0 && e == 0 && errno != EINTR) e = errno;
  if (e == 0 && ::rename(tmp.c_str(), path.c_str()) != 0) e = errno;
  if (e != 0) {
    ::unlink(tmp.c_str());
    return write_error(given, e);
  }
  // The rename itself on the disk: sync the directory (best effort: not every file system can).
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  int dir_fd = -1;
  if (open_errno(dir.c_str(), O_RDONLY | O_DIRECTORY, 0, dir_fd) == 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
  return {};
}

Result<void> create_output_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return write_error(dir, ec.value());
  // create_directories reports no error for a file of that name; it is no directory to write in.
  if (!std::filesystem::is_directory(dir, ec)) {
    return Error{ErrorCode::kIo,
                 "cannot write " + dir.string() + ": it exists and is not a directory"};
  }
  return {};
}

Result<LogFile> LogFile::open(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
    return Error{ErrorCode::kIo, "cannot write " + path.string() + ": it is a directory"};
  }
  const bool regular_or_new = ::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode);
  const int flags = O_WRONLY | (regular_or_new ? O_CREAT | O_TRUNC | O_APPEND : 0);
  int fd = -1;
  if (int e = open_errno(path.c_str(), flags, 0666, fd); e != 0) return write_error(path, e);
  return LogFile(fd, path.string());
}

LogFile::LogFile(LogFile&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      path_(std::move(other.path_)),
      appends_(other.appends_),
      failed_(other.failed_),
      first_error_(std::move(other.first_error_)) {}

LogFile& LogFile::operator=(LogFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
    appends_ = other.appends_;
    failed_ = other.failed_;
    first_error_ = std::move(other.first_error_);
  }
  return *this;
}

LogFile::~LogFile() {
  if (fd_ >= 0) ::close(fd_);
}

void LogFile::record(int error, bool lost_write) {
  if (lost_write) ++failed_;
  if (!first_error_) first_error_ = write_error(path_, error).message;
}

bool LogFile::append(std::string_view text) {
  ++appends_;
  if (fd_ < 0) {
    record(EBADF);
    return false;
  }
  if (const int e = write_all(fd_, text); e != 0) {
    record(e);
    return false;
  }
  return true;
}

Result<void> LogFile::close() {
  if (fd_ >= 0) {
    const int fd = std::exchange(fd_, -1);
    if (::close(fd) != 0 && errno != EINTR) record(errno, false);
  }
  if (!first_error_) return {};
  if (failed_ == 0) return Error{ErrorCode::kIo, *first_error_};
  return Error{ErrorCode::kIo, *first_error_ + " (" + std::to_string(failed_) + " of " +
                                   std::to_string(appends_) + " writes lost)"};
}

}  // namespace sewerplan
