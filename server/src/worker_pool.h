// SPDX-License-Identifier: MIT
// The station's connection workers: httplib serves each connection on one worker from accept to
// close, so a connection that sends nothing still holds one (until its idle timeout). A fixed pool
// of a few workers is held by a few idle connections, and every other request waits behind them
// (200 idle connections delayed each request by about 10 s with 32 workers). This pool starts a
// worker whenever a connection would wait for one, up to `max_workers`; beyond that, connections
// wait their turn in arrival order. Workers stay until shutdown(). Private to server/src.
//
//   http.new_task_queue = [] { return new WorkerPool(256); };
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include <httplib.h>

namespace sewerplan::server {

class WorkerPool final : public httplib::TaskQueue {
 public:
  explicit WorkerPool(std::size_t max_workers);
  ~WorkerPool() override;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Runs `job` on an idle worker, a new one if none is idle and the limit allows, else when one is.
  void enqueue(std::function<void()> job) override;
  // Runs the jobs queued, then joins every worker. Enqueue nothing after it.
  void shutdown() override;

 private:
  void work();

  const std::size_t max_workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  std::vector<std::thread> threads_;
  std::size_t idle_ = 0;  // workers waiting for a job
  bool stopping_ = false;
};

}  // namespace sewerplan::server
