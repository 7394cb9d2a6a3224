// SPDX-License-Identifier: MIT
#include "subprocess.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sewerplan::compare {
namespace {

// In the child, between fork and exec: only async-signal-safe calls.
[[noreturn]] void exec_child(const std::vector<char*>& argv, const RunLimits& limits,
                             int error_pipe) {
  setpgid(0, 0);
  if (limits.memory_limit_mb > 0) {
    const rlim_t bytes = static_cast<rlim_t>(limits.memory_limit_mb) * 1024 * 1024;
    const rlimit limit{bytes, bytes};
    setrlimit(RLIMIT_AS, &limit);
  }
  auto redirect = [](const std::string& path, int fd) {
    const int file = open(path.empty() ? "/dev/null" : path.c_str(),
                          O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (file >= 0) dup2(file, fd);
  };
  redirect(limits.stdout_path, STDOUT_FILENO);
  redirect(limits.stderr_path, STDERR_FILENO);
  const int null_in = open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (null_in >= 0) dup2(null_in, STDIN_FILENO);
  if (!limits.directory.empty() && chdir(limits.directory.c_str()) != 0) {
    const int e = errno;
    [[maybe_unused]] auto n = write(error_pipe, &e, sizeof e);
    _exit(127);
  }
  execv(argv[0], argv.data());
  const int e = errno;
  [[maybe_unused]] auto n = write(error_pipe, &e, sizeof e);
  _exit(127);
}

}  // namespace

RunResult run_process(const std::vector<std::string>& args, const RunLimits& limits) {
  RunResult result;
  std::vector<std::string> argv_storage = args;
  std::vector<char*> argv;
  for (std::string& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);

  int error_pipe[2];
  if (pipe2(error_pipe, O_CLOEXEC) != 0) {
    result.error = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    result.error = std::string("fork: ") + std::strerror(errno);
    close(error_pipe[0]);
    close(error_pipe[1]);
    return result;
  }
  if (pid == 0) exec_child(argv, limits, error_pipe[1]);
  setpgid(pid, pid);  // also here, so that the group exists before any kill below
  close(error_pipe[1]);
  int exec_errno = 0;
  const bool exec_failed = read(error_pipe[0], &exec_errno, sizeof exec_errno) > 0;
  close(error_pipe[0]);

  int status = 0;
  rusage usage{};
  const auto deadline = start + std::chrono::duration<double>(limits.time_limit_s);
  for (auto pause = std::chrono::microseconds(50);;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      result.error = std::string("wait4: ") + std::strerror(errno);
      return result;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      kill(-pid, SIGKILL);
      result.timed_out = true;
      wait4(pid, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(5000));
  }
  kill(-pid, SIGKILL);  // helpers the planner left behind
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  if (exec_failed) {
    result.error = args.front() + ": cannot run: " + std::strerror(exec_errno);
    return result;
  }
  result.started = true;
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

}  // namespace sewerplan::compare
