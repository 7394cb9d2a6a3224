// SPDX-License-Identifier: MIT
// BackgroundReplan: one replan on a thread of its own, while the robot waits or backs out, which
// the robot software cancels when a newer report arrives.
//
// It runs Replanner::report_failure (or Replanner::plan) on a std::jthread; cancel() (or the
// destructor) requests the thread's stop, which sets the cancel flag of the search's
// StopCondition (core/stop_condition.h): the replan gives up at the search's next check and
// get() answers kCancelled, without the safe fallback a synchronous plan() would compute. What the
// report taught the world model (the blockage, the closed passage) stays learnt; only the plan is
// discarded, and the newer report is planned from there:
//
//   std::optional<BackgroundReplan> replan;
//   replan.emplace(replanner, failure);          // the robot backs off meanwhile
//   ... a newer failure arrives:
//   replan->cancel();  (void)replan->get();      // returns within the search's next check
//   replan.emplace(replanner, newer_failure);
//   Result<PlanResponse> r = replan->get();      // waits for the answer
//
// Thread safety: cancel() and ready() may be called from any thread, at any time; get() from one
// thread at a time. The Replanner is not thread-safe: while a BackgroundReplan runs (until get()
// returned or it is destroyed), nothing else may use it.
#pragma once

#include <atomic>
#include <future>
#include <optional>
#include <string>
#include <thread>

#include "sewerplan/core/result.h"
#include "sewerplan/executor/replanner.h"

namespace sewerplan::executor {

class BackgroundReplan {
 public:
  // Starts report_failure(*failure), or plan(reason) when there is no failure.
  BackgroundReplan(Replanner& replanner, std::optional<Failure> failure,
                   std::string reason = "replan");
  // Cancels and waits for the thread.
  ~BackgroundReplan();
  BackgroundReplan(const BackgroundReplan&) = delete;
  BackgroundReplan& operator=(const BackgroundReplan&) = delete;

  // Asks the replan to stop; returns at once.
  void cancel();
  // The answer is there: get() will not wait.
  bool ready() const;
  // Waits for the answer: the Replanner's, or kCancelled when cancel() came first. Once only.
  Result<PlanResponse> get();

 private:
  std::atomic<bool> cancel_{false};
  std::future<Result<PlanResponse>> answer_;
  std::jthread thread_;  // last: started after the members it uses, stopped first
};

}  // namespace sewerplan::executor
