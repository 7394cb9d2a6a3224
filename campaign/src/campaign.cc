// SPDX-License-Identifier: MIT
// The guarded, parallel campaign runner (campaign.h).
#include "sewerplan/campaign/campaign.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <functional>
#include <latch>
#include <mutex>
#include <string>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sewerplan::campaign {
namespace {

using SteadyTime = std::chrono::steady_clock;

double seconds_since(SteadyTime::time_point start) {
  return std::chrono::duration<double>(SteadyTime::now() - start).count();
}

RunRecord compute(const SewerMap& map, const Mission& mission, const RunSettings& settings,
                  std::size_t index) {
  RunRecord record;
  record.index = index;
  record.seed = run_seed(settings.campaign_seed, index);
  Result<RunResult> r = run_one(map, mission, settings, index);
  if (!r.has_value()) {
    // Only bad rates fail, and those are checked before a campaign starts.
    record.status = RunRecord::Status::kCrash;
    record.detail = "error: " + r.error().message;
    return record;
  }
  record.wall_s = r->wall_s;
  record.result = std::move(*r);
  return record;
}

void inject(const CampaignOptions& options, std::size_t index) {
  const auto it = options.inject.find(index);
  if (it == options.inject.end()) return;
  if (it->second == InjectedFault::kCrash) {
    ::raise(SIGSEGV);
  } else {
    for (;;) ::pause();
  }
}

std::string signal_text(int sig) {
  const char* name = ::strsignal(sig);
  return "signal " + std::to_string(sig) + (name != nullptr ? std::string(" (") + name + ")" : "");
}

// What the guarded workers share with the thread that called run_campaign.
//
// A fork copies only the forking thread, so a lock another thread holds at that moment stays
// locked in the child for ever. glibc's malloc guards its own locks around fork, but not every
// allocator does (ASan's before LLVM 17 does not; a child then waited on it for ever), so nothing
// of ours allocates while a worker forks: the workers' own bookkeeping runs under `heap`, which a
// worker releases only while it waits for its child, and the caller's progress callback, which
// runs under no lock of ours (a slow one must not hold up the workers), sets `reporting` meanwhile:
// no child is forked until it returns.
struct Workers {
  std::mutex heap;
  std::condition_variable changed;  // a run finished, a worker ended, or the callback returned
  std::deque<std::pair<std::size_t, double>> finished;  // not yet reported: (slot, elapsed_s)
  std::size_t ended = 0;                                // workers that have ended
  bool reporting = false;                               // the progress callback runs
};

// Runs one run in a forked child; the child writes its record as a line to a pipe. Nothing when
// options.stop fired meanwhile (the child is killed, or none was forked). `heap` holds
// shared.heap, and is released while the worker waits (Workers).
std::optional<RunRecord> guarded(const SewerMap& map, const Mission& mission,
                                 const RunSettings& settings, const CampaignOptions& options,
                                 std::size_t index, Workers& shared,
                                 std::unique_lock<std::mutex>& heap) {
  while (shared.reporting) {
    if (options.stop.interrupted()) return std::nullopt;
    shared.changed.wait_for(heap, std::chrono::milliseconds(20));
  }
  const auto start = SteadyTime::now();
  RunRecord failed;
  failed.index = index;
  failed.seed = run_seed(settings.campaign_seed, index);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    failed.status = RunRecord::Status::kCrash;
    failed.detail = std::string("cannot create a pipe: ") + std::strerror(errno);
    return failed;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    failed.status = RunRecord::Status::kCrash;
    failed.detail = std::string("cannot fork: ") + std::strerror(errno);
    return failed;
  }
  if (pid == 0) {
    ::close(fds[0]);
    inject(options, index);
    const std::string line = run_json_line(compute(map, mission, settings, index)) + "\n";
    std::size_t written = 0;
    while (written < line.size()) {
      const ssize_t n = ::write(fds[1], line.data() + written, line.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) ::_exit(3);
      written += static_cast<std::size_t>(n);
    }
    ::_exit(0);
  }
  ::close(fds[1]);
  // Other workers' children may hold this pipe's write end too (fork copies every descriptor), so
  // the end of the line, or the child's exit, says when the record is complete, not end of file.
  std::string text;
  int status = 0;
  bool exited = false;
  bool hung = false;
  for (;;) {
    pollfd p{fds[0], POLLIN, 0};
    heap.unlock();  // waiting allocates nothing
    const int ready = ::poll(&p, 1, 20);
    heap.lock();
    if (ready > 0) {
      char buffer[4096];
      const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
      if (n > 0) text.append(buffer, static_cast<std::size_t>(n));
    }
    if (!exited && ::waitpid(pid, &status, WNOHANG) == pid) exited = true;
    const bool complete = !text.empty() && text.back() == '\n';
    if (complete && !exited) {
      ::waitpid(pid, &status, 0);
      exited = true;
    }
    if (exited) {
      // Whatever the child wrote before it exited is in the pipe now.
      ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
      char buffer[4096];
      for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) {
        text.append(buffer, static_cast<std::size_t>(n));
      }
      break;
    }
    if (options.stop.interrupted()) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      ::close(fds[0]);
      return std::nullopt;
    }
    if (seconds_since(start) > options.timeout_s) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      hung = true;
      break;
    }
  }
  ::close(fds[0]);
  failed.wall_s = seconds_since(start);
  if (hung) {
    failed.status = RunRecord::Status::kHang;
    failed.detail = "still running after " + std::to_string(options.timeout_s) + " s; killed";
    return failed;
  }
  if (WIFSIGNALED(status)) {
    failed.status = RunRecord::Status::kCrash;
    failed.detail = signal_text(WTERMSIG(status));
    return failed;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty() || text.back() != '\n') {
    failed.status = RunRecord::Status::kCrash;
    failed.detail =
        "exited with status " + std::to_string(WEXITSTATUS(status)) + " without a result";
    return failed;
  }
  text.pop_back();
  Result<RunRecord> record = parse_run_line(text, "child of run " + std::to_string(index), 1);
  if (!record.has_value()) {
    failed.status = RunRecord::Status::kCrash;
    failed.detail = "unreadable result: " + record.error().message;
    return failed;
  }
  return *record;
}

// The guarded runs: `jobs` worker threads take the runs in index order, and this thread reports
// each finished one through `report` (with no lock held) as it comes.
void run_guarded(const SewerMap& map, const Mission& mission, const RunSettings& settings,
                 const CampaignOptions& options, const std::vector<std::size_t>& indices,
                 std::vector<std::optional<RunRecord>>& records, std::size_t jobs,
                 const std::function<void(std::size_t, double)>& report,
                 SteadyTime::time_point start) {
  Workers shared;
  std::atomic<std::size_t> next{0};
  // A thread's start and end allocate in the thread itself (thread-local caches), outside
  // `heap`: no worker forks before every worker has started, nor while one is ending.
  std::latch started(static_cast<std::ptrdiff_t>(jobs));
  std::latch finished(static_cast<std::ptrdiff_t>(jobs));
  auto work = [&] {
    started.arrive_and_wait();
    for (std::size_t k; !options.stop.interrupted() && (k = next++) < indices.size();) {
      std::unique_lock heap(shared.heap);
      std::optional<RunRecord> r =
          guarded(map, mission, settings, options, indices[k], shared, heap);
      if (!r) break;  // stopped
      records[k] = std::move(r);
      shared.finished.emplace_back(k, seconds_since(start));
      shared.changed.notify_all();
    }
    finished.arrive_and_wait();
    const std::lock_guard heap(shared.heap);
    ++shared.ended;
    shared.changed.notify_all();
  };
  std::vector<std::thread> threads;
  threads.reserve(jobs);
  {
    // Starting the threads allocates: no worker may fork meanwhile.
    const std::lock_guard starting(shared.heap);
    for (std::size_t j = 0; j < jobs; ++j) threads.emplace_back(work);
  }
  // Every finished run is reported, those that finished after a stop too.
  std::unique_lock lock(shared.heap);
  for (;;) {
    shared.changed.wait(lock, [&] { return !shared.finished.empty() || shared.ended == jobs; });
    if (shared.finished.empty()) break;
    const auto [k, elapsed_s] = shared.finished.front();
    shared.finished.pop_front();
    shared.reporting = true;
    lock.unlock();
    report(k, elapsed_s);
    lock.lock();
    shared.reporting = false;
    shared.changed.notify_all();
  }
  lock.unlock();
  for (std::thread& t : threads) t.join();
}

}  // namespace

RunSettings run_settings(const CampaignSpec& spec) {
  return {.rates = spec.rates,
          .campaign_seed = spec.seed,
          .push_allowed = spec.push_allowed,
          .planner_time_limit_s = spec.planner_time_limit_s,
          .max_strand_risk = spec.max_strand_risk,
          .faults_from_condition = spec.faults_from_condition,
          .risk = spec.risk == "expected" ? domain::kDefaultRiskCosts : domain::RiskCosts{},
          // Checked when the spec was made (the CLI) or read (parse_campaign_json).
          .world_errors = [&] {
            const Result<hal::WorldErrorProfile> p = hal::parse_world_errors(spec.world_errors);
            return p.has_value() ? *p : hal::WorldErrorProfile{};
          }()};
}

std::size_t campaign_jobs(const CampaignSpec& spec, const CampaignOptions& options) {
  if (!options.guard) return 1;
  std::size_t runs = 1;
  if (!options.only) {
    runs = 0;
    for (std::size_t i = 0; i < spec.runs; ++i) runs += spec.in_shard(i) ? 1U : 0U;
  }
  return std::max<std::size_t>(1, std::min(options.jobs, runs));
}

std::vector<RunRecord> run_campaign(const SewerMap& map, const Mission& mission,
                                    const CampaignSpec& spec, const CampaignOptions& options) {
  const RunSettings settings = run_settings(spec);
  std::vector<std::size_t> indices;
  if (options.only) {
    indices.push_back(*options.only);
  } else {
    for (std::size_t i = 0; i < spec.runs; ++i) {
      if (spec.in_shard(i)) indices.push_back(i);
    }
  }
  std::vector<std::optional<RunRecord>> records(indices.size());
  Progress progress{.total = indices.size()};
  const auto start = SteadyTime::now();
  // Counts run k in `progress` and tells the caller's callback; with no lock held.
  const auto report = [&](std::size_t k, double elapsed_s) {
    ++progress.done;
    if (records[k]->status != RunRecord::Status::kOk) ++progress.failed;
    progress.elapsed_s = elapsed_s;
    progress.last = &*records[k];
    if (options.progress) options.progress(progress);
    progress.last = nullptr;
  };
  if (!options.guard) {
    // In this thread, one run at a time; the stop is honoured between runs.
    for (std::size_t k = 0; k < indices.size() && !options.stop.interrupted(); ++k) {
      records[k] = compute(map, mission, settings, indices[k]);
      report(k, seconds_since(start));
    }
  } else {
    run_guarded(
        map, mission, settings, options, indices, records, campaign_jobs(spec, options),
        [&](std::size_t k, double elapsed_s) { report(k, elapsed_s); }, start);
  }
  std::vector<RunRecord> finished_runs;
  finished_runs.reserve(records.size());
  for (std::optional<RunRecord>& r : records) {
    if (r) finished_runs.push_back(std::move(*r));
  }
  return finished_runs;
}

Result<std::map<std::size_t, InjectedFault>> parse_injections(std::string_view text) {
  std::map<std::size_t, InjectedFault> out;
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string item(text.substr(0, comma));
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const std::size_t colon = item.find(':');
    const std::string kind = item.substr(0, colon);
    std::size_t run = 0;
    bool ok = colon != std::string::npos && (kind == "crash" || kind == "hang");
    if (ok) {
      const std::string number = item.substr(colon + 1);
      ok = !number.empty() && number.find_first_not_of("0123456789") == std::string::npos &&
           number.size() < 10;
      if (ok) run = std::stoul(number);
    }
    if (!ok) {
      return Error{ErrorCode::kInvalidArgument,
                   "SEWERPLAN_CAMPAIGN_INJECT: expected crash:RUN or hang:RUN, got '" + item + "'"};
    }
    out[run] = kind == "crash" ? InjectedFault::kCrash : InjectedFault::kHang;
  }
  return out;
}

}  // namespace sewerplan::campaign
