// SPDX-License-Identifier: MIT
#include "reach_barriers.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>
#include <tuple>

#include "sewerplan/core/message_text.h"
#include "sewerplan/core/passage_motion.h"

namespace sewerplan::domain::detail {
namespace {

// As judge_passage: a 90 degree turn computed with rounding error still counts as 90.
constexpr double kLimitTolerance = 1e-9;

std::string number_text_fixed(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << v;
  return out.str();
}

class Barriers {
 public:
  Barriers(const PositionGraph& graph, const Mission& mission)
      : graph_(graph), map_(graph.map()), mission_(mission), profile_(mission.profile) {}

  // Why the robot cannot enter pipe p (from a manhole or through a passage), or nothing.
  void pipe_entry(PipeId p) {
    const Pipe& pipe = map_.pipe(p);
    if (!graph_.pipe_fits(p)) {
      const bool narrow = pipe.diameter_m < profile_.min_pipe_diameter_m;
      const LimitText t = limit_text_fixed(
          pipe.diameter_m, narrow ? profile_.min_pipe_diameter_m : profile_.max_pipe_diameter_m);
      add("pipe:" + pipe.name, "pipe " + pipe.name + " is " + t.value + " m, " +
                                   (narrow ? "narrower" : "wider") + " than " + profile_.name +
                                   "'s " + t.limit + " m");
    }
    if (std::find(mission_.closed_pipes.begin(), mission_.closed_pipes.end(), p) !=
        mission_.closed_pipes.end()) {
      add("closed:" + pipe.name, "pipe " + pipe.name + " is closed");
    }
  }

  // Why the robot cannot pass manhole m from slot i into slot j, or nothing.
  void passage(ManholeId m, SlotIndex i, SlotIndex j) {
    pipe_entry(map_.slot(m, j).pipe);
    // Into a pipe the robot does not fit, or out of one it is not in, the turn and step are moot.
    if (!graph_.pipe_fits(map_.slot(m, j).pipe) || !graph_.pipe_fits(map_.slot(m, i).pipe)) return;
    const std::string name = passage_name(m, i, j);
    const auto key = [&](const char* kind) {
      return std::string(kind) + map_.manhole(m).name + ":" +
             std::to_string(std::min(i.value(), j.value())) + ":" +
             std::to_string(std::max(i.value(), j.value()));
    };
    const PassageVerdict v = judge_passage(map_, profile_, mission_.passage_motion.get(), m, i, j);
    if (!v.allowed && v.by_motion) {
      const std::string why =
          v.motion != nullptr && !v.motion->reason.empty() ? v.motion->reason : "none was found";
      add(key("motion:"), name + " has no planned motion: " + why);
    } else if (!v.allowed) {
      std::string why;
      if (v.turn_deg > profile_.max_turn_deg + kLimitTolerance) {
        const LimitText t = limit_text_fixed(v.turn_deg, profile_.max_turn_deg);
        why = "turns " + t.value + " deg, beyond " + profile_.name + "'s " + t.limit +
              " deg turn limit";
      }
      if (std::abs(v.step_m) > profile_.max_step_m + kLimitTolerance) {
        const LimitText t = limit_text_fixed(std::abs(v.step_m), profile_.max_step_m);
        why += (why.empty() ? "" : " and ") + std::string(v.step_m > 0 ? "climbs" : "drops") +
               " a step of " + t.value + " m, beyond " + profile_.name + "'s " + t.limit +
               " m step limit";
      }
      if (!why.empty()) add(key("limit:"), name + " " + why);
    }
    for (const ClosedPassage& c : mission_.closed_passages) {
      if (c.manhole == m && ((c.from == i && c.to == j) || (c.from == j && c.to == i))) {
        add(key("closed:"), name + " is closed");
        break;
      }
    }
  }

  // Why the robot cannot drive pipe p from offset x to offset `to`, or nothing.
  void drive(PipeId p, double x, double to) {
    if (!graph_.blocked_between(p, x, to)) return;
    const std::optional<Blockage> b = blockage_between(mission_, p, x, to);
    if (!b) return;
    const std::string text =
        "pipe " + map_.pipe(p).name + " is blocked at " + number_text_fixed(b->offset_m) + " m";
    add("blockage:" + text, text);
  }

  std::vector<std::string> take() { return std::move(found_); }

 private:
  std::string passage_name(ManholeId m, SlotIndex i, SlotIndex j) const {
    return "manhole " + map_.manhole(m).name + " from slot " + std::to_string(to_paper_number(i)) +
           " (pipe " + map_.pipe(map_.slot(m, i).pipe).name + ") to slot " +
           std::to_string(to_paper_number(j)) + " (pipe " + map_.pipe(map_.slot(m, j).pipe).name +
           ")";
  }
  void add(const std::string& key, std::string text) {
    if (seen_.insert(key).second) found_.push_back(std::move(text));
  }

  const PositionGraph& graph_;
  const SewerMap& map_;
  const Mission& mission_;
  const RobotProfile& profile_;
  std::set<std::string> seen_;
  std::vector<std::string> found_;
};

// Every position from which a target is reached by moves that ignore the limits and the closures
// (the physical connections of the network) without passing through `reached` (what the robot
// reaches is not expanded: a way out of it and back in, into a dead end, is no way to a target).
std::vector<bool> can_reach_ignoring_limits(const PositionGraph& graph,
                                            std::span<const Node> targets,
                                            const std::vector<bool>& reached) {
  const SewerMap& map = graph.map();
  std::vector<bool> seen(graph.size(), false);
  std::vector<Node> stack;
  const auto visit = [&](Node n) {
    if (seen[n]) return;
    seen[n] = true;
    if (!reached[n]) stack.push_back(n);
  };
  for (Node t : targets) {
    visit(t);
    if (graph.is_extra_spot(t)) {  // a task action reaches it from its pipe's ends
      const PipeId p = *graph.pipe_of(t);
      visit(graph.pipe_end(p, 0));
      visit(graph.pipe_end(p, 1));
    }
  }
  while (!stack.empty()) {
    const Node n = stack.back();
    stack.pop_back();
    const RobotPosition at = graph.position(n);
    if (const auto* slot = std::get_if<AtSlot>(&at)) {
      // Out of the slot's pipe, from either end or a spot in it.
      const PipeId p = map.slot(slot->manhole, slot->slot).pipe;
      visit(graph.pipe_end(p, 0));
      visit(graph.pipe_end(p, 1));
      for (Node s : graph.extra_spots_in(p)) visit(s);
    } else if (const auto* in = std::get_if<InPipe>(&at); in && !graph.is_extra_spot(n)) {
      // A pipe's end is entered from its manhole, or from another slot of it.
      const Pipe& pipe = map.pipe(in->pipe);
      const std::size_t e = in->offset_m <= 0 ? 0 : 1;
      if (!pipe.ends[e].manhole) continue;
      const ManholeId m = *pipe.ends[e].manhole;
      visit(graph.in_manhole(m));
      for (std::uint16_t s = 0; s < map.manhole(m).slot_count; ++s) {
        if (s != pipe.ends[e].slot.value()) visit(graph.at_slot(m, SlotIndex{s}));
      }
    }
  }
  return seen;
}

}  // namespace

ReachDiagnosis diagnose_reach(const PositionGraph& graph, const Mission& mission,
                              std::span<const Node> origins, std::span<const Node> targets) {
  ReachDiagnosis d;
  // What the robot reaches, with no bound on the battery.
  std::vector<bool> reached(graph.size(), false);
  std::vector<Node> stack;
  for (Node o : origins) {
    if (!reached[o]) stack.push_back(o);
    reached[o] = true;
  }
  while (!stack.empty()) {
    const Node n = stack.back();
    stack.pop_back();
    graph.for_each_successor(n, [&](Node next, Cost) {
      if (reached[next]) return;
      reached[next] = true;
      stack.push_back(next);
    });
  }
  const std::vector<bool> useful = can_reach_ignoring_limits(graph, targets, reached);
  for (Node t : targets) {
    if (reached[t]) d.reachable = true;
    if (graph.is_extra_spot(t)) {
      const PipeId p = *graph.pipe_of(t);
      if (reached[graph.pipe_end(p, 0)] || reached[graph.pipe_end(p, 1)]) d.reachable = true;
    }
  }
  if (d.reachable) return d;
  // The moves out of the reached part into the useful part, and what forbids each.
  const SewerMap& map = graph.map();
  Barriers barriers(graph, mission);
  for (Node n = 0; n < graph.size(); ++n) {
    if (!reached[n]) continue;
    const RobotPosition at = graph.position(n);
    if (const auto* in_manhole = std::get_if<InManhole>(&at)) {
      for (const Slot& s : map.slots(in_manhole->manhole)) {
        const Node next = graph.pipe_end(s.pipe, s.pipe_end);
        if (!reached[next] && useful[next]) barriers.pipe_entry(s.pipe);
      }
    } else if (const auto* slot = std::get_if<AtSlot>(&at)) {
      const auto slots = map.slots(slot->manhole);
      for (std::uint16_t j = 0; j < slots.size(); ++j) {
        const Node next = graph.pipe_end(slots[j].pipe, slots[j].pipe_end);
        if (j == slot->slot.value() || reached[next] || !useful[next]) continue;
        barriers.passage(slot->manhole, slot->slot, SlotIndex{j});
      }
    } else {
      const auto& in = std::get<InPipe>(at);
      const Pipe& pipe = map.pipe(in.pipe);
      for (std::size_t e = 0; e < 2; ++e) {
        if (!pipe.ends[e].manhole) continue;
        const Node next = graph.at_slot(*pipe.ends[e].manhole, pipe.ends[e].slot);
        if (reached[next] || !useful[next]) continue;
        barriers.drive(in.pipe, in.offset_m, e == 0 ? 0.0 : pipe.length_m);
      }
    }
  }
  d.barriers = barriers.take();
  return d;
}

std::string barrier_list(const ReachDiagnosis& diagnosis, std::size_t shown) {
  std::string out;
  const std::size_t n = diagnosis.barriers.size();
  for (std::size_t i = 0; i < n && i < shown; ++i) {
    out += (i == 0 ? "" : "; ") + diagnosis.barriers[i];
  }
  if (n > shown) out += "; and " + std::to_string(n - shown) + " more";
  return out;
}

}  // namespace sewerplan::domain::detail
