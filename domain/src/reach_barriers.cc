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

  // The (key, text) of each barrier found since the last call.
  std::vector<std::pair<std::string, std::string>> take() { return std::move(found_); }

 private:
  std::string passage_name(ManholeId m, SlotIndex i, SlotIndex j) const {
    return "manhole " + map_.manhole(m).name + " from slot " + std::to_string(to_paper_number(i)) +
           " (pipe " + map_.pipe(map_.slot(m, i).pipe).name + ") to slot " +
           std::to_string(to_paper_number(j)) + " (pipe " + map_.pipe(map_.slot(m, j).pipe).name +
           ")";
  }
  void add(std::string key, std::string text) {
    found_.emplace_back(std::move(key), std::move(text));
  }

  const PositionGraph& graph_;
  const SewerMap& map_;
  const Mission& mission_;
  const RobotProfile& profile_;
  std::vector<std::pair<std::string, std::string>> found_;
};

// The parts of the network the robot does not reach, each joined by moves that ignore the limits
// and the closures without passing through what it reaches (a way out of it and back in, into a
// dead end, is no way to a target): a union of the positions at each manhole (its slots and the
// pipe ends there) and of each pipe's positions with the slots at its ends.
class Parts {
 public:
  Parts(const PositionGraph& graph, const std::vector<bool>& reached)
      : parent_(graph.size()), reached_(reached) {
    for (Node n = 0; n < parent_.size(); ++n) parent_[n] = n;
    const SewerMap& map = graph.map();
    for (ManholeId m : map.manhole_ids()) {
      std::optional<Node> first;
      const auto slots = map.slots(m);
      for (std::uint16_t s = 0; s < slots.size(); ++s) {
        for (Node n :
             {graph.at_slot(m, SlotIndex{s}), graph.pipe_end(slots[s].pipe, slots[s].pipe_end)}) {
          if (reached_[n]) continue;
          if (first) join(*first, n);
          first = first.value_or(n);
        }
      }
    }
    for (PipeId p : map.pipe_ids()) {
      const Pipe& pipe = map.pipe(p);
      std::vector<Node> in_pipe = {graph.pipe_end(p, 0), graph.pipe_end(p, 1)};
      for (Node spot : graph.extra_spots_in(p)) in_pipe.push_back(spot);
      for (std::size_t e = 0; e < 2; ++e) {
        if (!pipe.ends[e].manhole) continue;
        const Node slot = graph.at_slot(*pipe.ends[e].manhole, pipe.ends[e].slot);
        for (Node n : in_pipe) join(slot, n);
      }
    }
  }
  Node of(Node n) {
    while (parent_[n] != n) n = parent_[n] = parent_[parent_[n]];
    return n;
  }

 private:
  void join(Node a, Node b) {
    if (reached_[a] || reached_[b]) return;
    a = of(a);
    b = of(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }
  std::vector<Node> parent_;
  const std::vector<bool>& reached_;
};

}  // namespace

std::vector<bool> reachable_from(const PositionGraph& graph, std::span<const Node> origins) {
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
  return reached;
}

ReachDiagnoser::ReachDiagnoser(const PositionGraph& graph, const Mission& mission,
                               std::vector<bool> reached)
    : graph_(graph), reached_(std::move(reached)) {
  // The moves out of the reached part into the rest, what forbids each, and the part it leads to.
  const SewerMap& map = graph.map();
  Parts parts(graph, reached_);
  part_.resize(graph.size());
  for (Node n = 0; n < graph.size(); ++n) part_[n] = parts.of(n);
  Barriers barriers(graph, mission);
  const auto found = [&](Node next) {
    for (auto& [key, text] : barriers.take()) {
      if (seen_.insert({part_[next], key}).second) {
        found_.push_back({part_[next], std::move(key), std::move(text)});
      }
    }
  };
  for (Node n = 0; n < graph.size(); ++n) {
    if (!reached_[n]) continue;
    const RobotPosition at = graph.position(n);
    if (const auto* in_manhole = std::get_if<InManhole>(&at)) {
      for (const Slot& s : map.slots(in_manhole->manhole)) {
        const Node next = graph.pipe_end(s.pipe, s.pipe_end);
        if (reached_[next]) continue;
        barriers.pipe_entry(s.pipe);
        found(next);
      }
    } else if (const auto* slot = std::get_if<AtSlot>(&at)) {
      const auto slots = map.slots(slot->manhole);
      for (std::uint16_t j = 0; j < slots.size(); ++j) {
        const Node next = graph.pipe_end(slots[j].pipe, slots[j].pipe_end);
        if (j == slot->slot.value() || reached_[next]) continue;
        barriers.passage(slot->manhole, slot->slot, SlotIndex{j});
        found(next);
      }
    } else {
      const auto& in = std::get<InPipe>(at);
      const Pipe& pipe = map.pipe(in.pipe);
      for (std::size_t e = 0; e < 2; ++e) {
        if (!pipe.ends[e].manhole) continue;
        const Node next = graph.at_slot(*pipe.ends[e].manhole, pipe.ends[e].slot);
        if (reached_[next]) continue;
        barriers.drive(in.pipe, in.offset_m, e == 0 ? 0.0 : pipe.length_m);
        found(next);
      }
    }
  }
}

ReachDiagnosis ReachDiagnoser::diagnose(std::span<const Node> targets) const {
  ReachDiagnosis d;
  std::set<Node> parts;
  for (Node t : targets) {
    std::vector<Node> at = {t};
    if (graph_.is_extra_spot(t)) {  // a task action reaches it from its pipe's ends
      const PipeId p = *graph_.pipe_of(t);
      at.push_back(graph_.pipe_end(p, 0));
      at.push_back(graph_.pipe_end(p, 1));
    }
    for (Node n : at) {
      if (reached_[n]) d.reachable = true;
      parts.insert(part_[n]);
    }
  }
  if (d.reachable) return d;
  std::set<std::string> named;
  for (const Found& f : found_) {
    if (parts.count(f.part) != 0 && named.insert(f.key).second) d.barriers.push_back(f.text);
  }
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
