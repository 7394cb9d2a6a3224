// SPDX-License-Identifier: MIT
#include "support/brute_force.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <queue>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "sewerplan/domain/validator.h"

namespace sewerplan::testing {
namespace {

using domain::AtSlot;
using domain::InManhole;
using domain::InPipe;
using domain::PlanReplay;
using domain::PlanStep;

// A state exactly: the position's kind, IDs and offset bits, and one bit a task.
struct StateKey {
  std::uint8_t kind = 0;
  std::uint32_t object = 0;
  std::uint32_t slot = 0;
  std::uint64_t offset_bits = 0;
  std::vector<std::uint64_t> done;
  friend bool operator==(const StateKey&, const StateKey&) = default;
};

struct StateKeyHash {
  std::size_t operator()(const StateKey& k) const {
    std::size_t h = std::hash<std::uint64_t>{}(k.offset_bits);
    auto mix = [&h](std::uint64_t v) {
      h ^= std::hash<std::uint64_t>{}(v) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    };
    mix(k.kind);
    mix(k.object);
    mix(k.slot);
    for (std::uint64_t word : k.done) mix(word);
    return h;
  }
};

StateKey key_of(const PlanReplay& replay) {
  StateKey key;
  const domain::RobotPosition& position = replay.position();
  if (const auto* m = std::get_if<InManhole>(&position)) {
    key.kind = 0;
    key.object = m->manhole.value();
  } else if (const auto* s = std::get_if<AtSlot>(&position)) {
    key.kind = 1;
    key.object = s->manhole.value();
    key.slot = s->slot.value();
  } else {
    const auto& p = std::get<InPipe>(position);
    key.kind = 2;
    key.object = p.pipe.value();
    key.offset_bits = std::bit_cast<std::uint64_t>(p.offset_m);
  }
  const std::vector<bool>& done = replay.done();
  key.done.assign((done.size() + 63) / 64, 0);
  for (std::size_t i = 0; i < done.size(); ++i) {
    if (done[i]) key.done[i / 64] |= std::uint64_t{1} << (i % 64);
  }
  return key;
}

void add_task_steps(const Mission& mission, PipeId pipe, std::vector<PlanStep>& out) {
  for (TaskId id : mission.task_ids()) {
    const Task& task = mission.task(id);
    const auto* spot = std::get_if<PipeSpot>(&task.place);
    if (spot == nullptr || spot->pipe != pipe) continue;
    switch (task.kind) {
      case TaskKind::kTakeWaterSample:
        out.push_back(domain::TakeWaterSample{pipe, id});
        break;
      case TaskKind::kGoTo:
        out.push_back(domain::GoToPoint{pipe, id});
        break;
      case TaskKind::kInspectPipe:
        out.push_back(domain::InspectPipe{pipe, id, std::uint8_t{0}});
        out.push_back(domain::InspectPipe{pipe, id, std::uint8_t{1}});
        break;
    }
  }
}

void add_go_to_manhole(const Mission& mission, ManholeId m, std::vector<PlanStep>& out) {
  for (TaskId id : mission.task_ids()) {
    const Task& task = mission.task(id);
    const auto* at = std::get_if<ManholeId>(&task.place);
    if (task.kind == TaskKind::kGoTo && at != nullptr && *at == m) {
      out.push_back(domain::GoToManhole{m, id});
    }
  }
}

// Every step worth trying from `position`; PlanReplay::apply decides which are executable.
std::vector<PlanStep> candidates(const SewerMap& map, const Mission& mission,
                                 const domain::RobotPosition& position) {
  std::vector<PlanStep> out;
  if (const auto* p = std::get_if<InPipe>(&position)) {
    const Pipe& pipe = map.pipe(p->pipe);
    for (const PipeEnd& end : pipe.ends) {
      if (end.manhole) out.push_back(domain::DrivePipeToManhole{p->pipe, *end.manhole});
    }
    add_task_steps(mission, p->pipe, out);
  } else if (const auto* s = std::get_if<AtSlot>(&position)) {
    const auto count = map.manhole(s->manhole).slot_count;
    for (std::uint16_t j = 0; j < count; ++j) {
      if (SlotIndex{j} != s->slot)
        out.push_back(domain::DriveManhole{s->manhole, s->slot, SlotIndex{j}});
    }
    add_go_to_manhole(mission, s->manhole, out);
  } else {
    const ManholeId m = std::get<InManhole>(position).manhole;
    for (const Slot& slot : map.slots(m)) out.push_back(domain::EnterPipe{m, slot.pipe});
    add_go_to_manhole(mission, m, out);
  }
  return out;
}

struct Node {
  PlanReplay replay;
  std::size_t parent;
  std::optional<PlanStep> step;  // empty at the start
  bool expanded = false;
};

BruteForceResult plan_to(const std::vector<Node>& nodes, std::size_t goal) {
  BruteForceResult result;
  result.cost_s = nodes[goal].replay.elapsed_s();
  for (std::size_t i = goal; nodes[i].step; i = nodes[i].parent) {
    result.plan.steps.push_back(*nodes[i].step);
  }
  std::reverse(result.plan.steps.begin(), result.plan.steps.end());
  return result;
}

}  // namespace

std::string_view to_string(BruteForceStatus status) {
  switch (status) {
    case BruteForceStatus::kFound:
      return "found";
    case BruteForceStatus::kNoPlan:
      return "no plan";
    case BruteForceStatus::kStateLimit:
      return "state limit reached";
  }
  return "found";
}

BruteForceOutcome brute_force_optimal_plan(const SewerMap& map, const Mission& mission,
                                           const domain::MissionProgress& start,
                                           std::size_t max_states) {
  std::vector<Node> nodes;
  std::unordered_map<StateKey, std::size_t, StateKeyHash> index;
  // (cost, node): the node index breaks ties, first reached first.
  using Entry = std::tuple<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  nodes.push_back(Node{PlanReplay(map, mission, start), 0, std::nullopt});
  index.emplace(key_of(nodes.front().replay), 0);
  open.emplace(0.0, 0);
  while (!open.empty()) {
    const auto [g, i] = open.top();
    open.pop();
    if (nodes[i].expanded || g != nodes[i].replay.elapsed_s()) continue;
    nodes[i].expanded = true;
    if (!nodes[i].replay.unmet_goal()) {
      return BruteForceOutcome(BruteForceStatus::kFound, plan_to(nodes, i), nodes.size());
    }
    for (const PlanStep& step : candidates(map, mission, nodes[i].replay.position())) {
      PlanReplay next = nodes[i].replay;
      if (!next.apply(step).has_value()) continue;
      auto [it, added] = index.emplace(key_of(next), nodes.size());
      if (added) {
        if (nodes.size() >= max_states) {
          return BruteForceOutcome(BruteForceStatus::kStateLimit, std::nullopt, nodes.size());
        }
        open.emplace(next.elapsed_s(), nodes.size());
        nodes.push_back(Node{std::move(next), i, step});
      } else if (Node& known = nodes[it->second];
                 !known.expanded && next.elapsed_s() < known.replay.elapsed_s()) {
        open.emplace(next.elapsed_s(), it->second);
        known = Node{std::move(next), i, step};
      }
    }
  }
  return BruteForceOutcome(BruteForceStatus::kNoPlan, std::nullopt, nodes.size());
}

BruteForceOutcome brute_force_optimal_plan(const SewerMap& map, const Mission& mission,
                                           std::size_t max_states) {
  return brute_force_optimal_plan(map, mission, domain::initial_progress(mission, map), max_states);
}

}  // namespace sewerplan::testing
