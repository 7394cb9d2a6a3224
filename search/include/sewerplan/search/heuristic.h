// SPDX-License-Identifier: MIT
// Heuristic: an estimate of the cost from a state to the goal, with preferred (helpful) actions.
//
// The heuristics are delete relaxations of the CompiledTask (Bonet and Geffner 2001, "Planning as
// heuristic search", AIJ 129): h_max (admissible: A* with it finds optimal plans), h_add, and FF's
// relaxed-plan heuristic (Hoffmann and Nebel 2001, "The FF planning system", JAIR 14), whose
// helpful actions guide enforced hill-climbing. The blind heuristic (0 at every state) makes A*
// uniform-cost search, for tests. kDeadEnd marks a state from which the relaxation reaches no
// goal, so the real task cannot either.
//
// A heuristic may watch a stop condition (issue 14: a cancel within 1 ms): evaluate() then checks
// it inside its own work (the relaxed task's construction, done on the first evaluation, and the
// relaxed exploration), and returns kInterrupted once it fires. The search engines watch their
// search()'s condition through their heuristic; kInterrupted is never returned without one.
//
//   std::unique_ptr<Heuristic> h = make_heuristic(HeuristicKind::kFf, task);
//   std::vector<ActionId> helpful;
//   Cost estimate = h->evaluate(task.initial_state(), &helpful);
//
// Thread-safety: a Heuristic keeps buffers between evaluate() calls, so one object serves one
// thread; distinct objects over one (read-only) CompiledTask may run concurrently.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/core/stop_condition.h"
#include "sewerplan/domain/compiled_task.h"

namespace sewerplan::search {

using domain::ActionId;
using domain::Cost;

enum class HeuristicKind { kFf, kAdd, kMax, kBlind };

std::string_view to_string(HeuristicKind kind);
std::optional<HeuristicKind> heuristic_from_string(std::string_view name);  // ff, add, max, blind
// The names heuristic_from_string reads, "ff, add, max, blind", for messages.
std::string heuristic_names();

class Heuristic {
 public:
  static constexpr Cost kDeadEnd = -1;
  // The watched stop condition fired during the evaluation: no estimate (the caller stops).
  static constexpr Cost kInterrupted = -2;

  virtual ~Heuristic() = default;
  // The estimate for `state` (one value per variable), kDeadEnd, or kInterrupted (only while a
  // stop condition is watched). If `preferred` is given, it is replaced by the heuristic's
  // preferred actions (none for heuristics without them).
  virtual Cost evaluate(std::span<const std::int32_t> state, std::vector<ActionId>* preferred) = 0;
  // Never above the true cost to the goal.
  virtual bool admissible() const = 0;
  virtual std::string_view name() const = 0;

  // The stop condition evaluate() checks (nullptr: none); it must outlive the watch.
  void watch(const StopCondition* stop) { watched_ = stop; }
  const StopCondition* watched() const { return watched_; }

 private:
  const StopCondition* watched_ = nullptr;
};

// `task` must outlive the heuristic.
std::unique_ptr<Heuristic> make_heuristic(HeuristicKind kind, const domain::CompiledTask& task);

}  // namespace sewerplan::search
