// SPDX-License-Identifier: MIT
#include "position_graph.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "sewerplan/core/check.h"
#include "sewerplan/core/map_queries.h"

namespace sewerplan::domain::detail {
namespace {

ClosedPassage normalised(ClosedPassage c) {
  if (c.to < c.from) std::swap(c.from, c.to);
  return c;
}

bool passage_less(const ClosedPassage& a, const ClosedPassage& b) {
  return std::tie(a.manhole, a.from, a.to) < std::tie(b.manhole, b.from, b.to);
}

}  // namespace

namespace {
// Entries handled between two checks of a stop condition while building or growing the arrays
// over a whole map: well under 0.1 ms each.
constexpr std::size_t kSlice = 16384;

bool fired(const StopCondition* stop) { return stop != nullptr && stop->interrupted().has_value(); }
}  // namespace

bool grow_in_slices(std::vector<bool>& bits, std::size_t size, const StopCondition* stop) {
  while (bits.size() < size) {
    if (fired(stop)) return false;
    bits.resize(std::min(size, bits.size() + kSlice * 8), false);
  }
  return true;
}

GraphCore::GraphCore(const SewerMap& map_in, const RobotProfile& profile_in,
                     std::shared_ptr<const PassageMotionTable> motion_in, const StopCondition* stop)
    : map(&map_in),
      profile(profile_in),
      motion(std::move(motion_in)),
      manholes(map_in.manhole_count()),
      pipes(map_in.pipe_count()),
      slots(map_in.slot_count()) {
  complete = build(map_in, stop);
}

bool GraphCore::build(const SewerMap& map_in, const StopCondition* stop) {
  fits.resize(pipes);
  for (PipeId p : map_in.pipe_ids()) {
    if (p.index() % kSlice == 0 && fired(stop)) return false;
    // Diameters are data, compared exactly, as the validator does.
    const double d = map_in.pipe(p).diameter_m;
    fits[p.index()] = d >= profile.min_pipe_diameter_m && d <= profile.max_pipe_diameter_m;
  }
  manhole_of_slot.resize(slots);
  passage_begin.resize(manholes + 1);
  std::size_t count = 0;
  for (ManholeId m : map_in.manhole_ids()) {
    if (m.index() % kSlice == 0 && fired(stop)) return false;
    const Manhole& manhole = map_in.manhole(m);
    for (std::uint16_t s = 0; s < manhole.slot_count; ++s) {
      manhole_of_slot[manhole.first_slot + s] = m.value();
    }
    passage_begin[m.index()] = count;
    count += std::size_t{manhole.slot_count} * manhole.slot_count;
  }
  passage_begin[manholes] = count;
  // Reserved at once, filled (and so paged in) slice by slice.
  passages.reserve(count);
  while (passages.size() < count) {
    if (fired(stop)) return false;
    passages.resize(std::min(count, passages.size() + kSlice), Cost{0});
  }
  return grow_in_slices(judged, manholes, stop);
}

bool GraphCore::serves(const SewerMap& map_in, const RobotProfile& profile_in,
                       const PassageMotionTable* motion_in) const {
  return complete && map == &map_in && manholes == map_in.manhole_count() &&
         pipes == map_in.pipe_count() && slots == map_in.slot_count() &&
         motion.get() == motion_in && profile == profile_in;
}

PositionGraph::PositionGraph(const SewerMap& map, const Mission& mission,
                             std::shared_ptr<GraphCore> core, const StopCondition* stop)
    : map_(map),
      mission_(mission),
      profile_(mission.profile),
      has_blockages_(!mission.blockages.empty()),
      manholes_(static_cast<Node>(map.manhole_count())),
      slots_(static_cast<Node>(map.slot_count())),
      pipes_(static_cast<Node>(map.pipe_count())),
      core_(core != nullptr
                ? std::move(core)
                : std::make_shared<GraphCore>(map, mission.profile, mission.passage_motion, stop)) {
  if (!core_->complete) return;  // stopped: the caller must not search it
  SEWER_CHECK(core_->serves(map, mission.profile, mission.passage_motion.get()),
              "a position graph's core built for another map or robot");
  drivable_ = core_->fits;
  for (PipeId p : mission.closed_pipes) drivable_[p.index()] = false;
  for (const ClosedPassage& c : mission.closed_passages) closed_passages_.push_back(normalised(c));
  std::sort(closed_passages_.begin(), closed_passages_.end(), passage_less);
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < mission.hazards.size(); ++i) {
    if (mission.hazards[i].probability > 0) order.push_back(static_cast<std::uint32_t>(i));
  }
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tie(mission.hazards[a].pipe, mission.hazards[a].offset_m) <
           std::tie(mission.hazards[b].pipe, mission.hazards[b].offset_m);
  });
  for (std::uint32_t i : order) hazards_.push_back(mission.hazards[i]);
  hazard_index_ = std::move(order);
  has_closed_pipes_ = !mission.closed_pipes.empty();
  auto mark = [](std::vector<bool>& bits, Node n) {
    if (bits.size() <= n) bits.resize(n + 1, false);
    bits[n] = true;
  };
  for (const Blockage& b : mission.blockages) {
    mark(irregular_, pipe_end(b.pipe, 0));
    mark(irregular_, pipe_end(b.pipe, 1));
  }
  for (const ClosedPassage& c : closed_passages_) {
    mark(irregular_, at_slot(c.manhole, c.from));
    mark(irregular_, at_slot(c.manhole, c.to));
  }
  for (const Hazard& h : hazards_) {
    mark(hazard_ends_, pipe_end(h.pipe, 0));
    mark(hazard_ends_, pipe_end(h.pipe, 1));
  }
}

bool PositionGraph::build_adjacency(const StopCondition* stop) {
  GraphCore& core = *core_;
  if (!core.adjacency_begin.empty()) return true;
  // The moves of a mission without closures, blockages or hazards on the same core, generated
  // from the map as a search would (the core has no adjacency yet, so they are).
  Mission plain;
  plain.profile = core.profile;
  plain.passage_motion = core.motion;
  const PositionGraph graph(map_, plain, core_);
  const Node nodes = manholes_ + slots_ + 2 * pipes_;
  std::vector<std::uint32_t> begin;
  std::vector<Node> to;
  std::vector<Cost> cost;
  begin.reserve(std::size_t{nodes} + 1);
  to.reserve(2 * std::size_t{nodes});
  cost.reserve(2 * std::size_t{nodes});
  bool free_passages = false;
  for (Node n = 0; n < nodes; ++n) {
    if (n % kSlice == 0 && fired(stop)) return false;
    begin.push_back(static_cast<std::uint32_t>(to.size()));
    const bool slot = n >= manholes_ && n < manholes_ + slots_;
    graph.for_each_successor(n, [&](Node next, Cost c) {
      to.push_back(next);
      cost.push_back(c);
      free_passages = free_passages || (slot && c == 0);
    });
  }
  SEWER_CHECK(to.size() < 0xffffffffU, "too many moves for the adjacency");
  begin.push_back(static_cast<std::uint32_t>(to.size()));
  core.adjacency_begin = std::move(begin);
  core.adjacency_to = std::move(to);
  core.adjacency_cost = std::move(cost);
  core.free_passages = free_passages;
  return true;
}

Cost PositionGraph::risk_cost_uncached(PipeId p, double a, double b, double weight_s) const {
  if (a > b) std::swap(a, b);
  auto it = std::lower_bound(hazards_.begin(), hazards_.end(), p,
                             [](const Hazard& h, PipeId id) { return h.pipe < id; });
  double unobstructed = 1;
  for (; it != hazards_.end() && it->pipe == p; ++it) {
    if (it->offset_m > a && it->offset_m < b)
      unobstructed *= 1 - std::clamp(it->probability, 0.0, 1.0);
  }
  return unobstructed < 1 ? to_cost((1 - unobstructed) * weight_s) : 0;
}

std::optional<double> PositionGraph::farthest_hazard(PipeId p, double from, double to,
                                                     const std::vector<bool>* insured) const {
  const double lo = std::min(from, to);
  const double hi = std::max(from, to);
  auto it = std::lower_bound(hazards_.begin(), hazards_.end(), p,
                             [](const Hazard& h, PipeId id) { return h.pipe < id; });
  std::optional<double> farthest;
  for (; it != hazards_.end() && it->pipe == p; ++it) {
    if (it->offset_m <= lo || it->offset_m >= hi) continue;
    if (insured != nullptr && !insured->empty()) {
      const std::uint32_t index = hazard_index_[static_cast<std::size_t>(it - hazards_.begin())];
      if (index >= insured->size() || !(*insured)[index]) continue;
    }
    if (!farthest || std::abs(it->offset_m - from) > std::abs(*farthest - from)) {
      farthest = it->offset_m;
    }
  }
  return farthest;
}

void PositionGraph::hazards_between(PipeId p, double from, double to,
                                    std::vector<std::pair<std::uint32_t, double>>& out) const {
  const double lo = std::min(from, to);
  const double hi = std::max(from, to);
  auto it = std::lower_bound(hazards_.begin(), hazards_.end(), p,
                             [](const Hazard& h, PipeId id) { return h.pipe < id; });
  for (; it != hazards_.end() && it->pipe == p; ++it) {
    if (it->offset_m <= lo || it->offset_m >= hi) continue;
    out.emplace_back(hazard_index_[static_cast<std::size_t>(it - hazards_.begin())],
                     std::abs(it->offset_m - from));
  }
}

Cost PositionGraph::route_risk(std::span<const Node> route, double weight_s) const {
  // Every GO action asks: without hazards or weight, skip walking its route (issue 16: at 1,000
  // manholes and 50 tasks, 13,000 routes).
  if (weight_s <= 0 || hazards_.empty()) return 0;
  Cost total = 0;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const std::optional<PipeId> p = pipe_of(route[i]);
    if (!p || pipe_of(route[i + 1])) continue;  // only DRIVE_PIPE_TO_MANHOLE crosses a pipe
    const RobotPosition to = position(route[i + 1]);
    const auto* slot = std::get_if<AtSlot>(&to);
    if (slot == nullptr) continue;
    const Slot& s = map_.slot(slot->manhole, slot->slot);
    total += risk_cost(*p, offset_of(route[i]), end_offset_m(map_.pipe(*p), s.pipe_end), weight_s);
  }
  return total;
}

Node PositionGraph::spot(PipeId pipe, double offset_m) {
  const Pipe& p = map_.pipe(pipe);
  if (offset_m <= 0) return pipe_end(pipe, 0);
  if (offset_m >= p.length_m) return pipe_end(pipe, 1);
  auto it = std::lower_bound(spots_by_pipe_.begin(), spots_by_pipe_.end(), pipe,
                             [](const auto& entry, PipeId id) { return entry.first < id; });
  if (it == spots_by_pipe_.end() || it->first != pipe) {
    it = spots_by_pipe_.insert(it, {pipe, {}});
  }
  for (Node n : it->second) {
    if (offset_of(n) == offset_m) return n;
  }
  const Node n = static_cast<Node>(manholes_ + slots_ + 2 * pipes_ + spots_.size());
  spots_.push_back({pipe, offset_m});
  it->second.push_back(n);
  return n;
}

Node PositionGraph::node(const RobotPosition& position) {
  if (const auto* m = std::get_if<InManhole>(&position)) return in_manhole(m->manhole);
  if (const auto* s = std::get_if<AtSlot>(&position)) return at_slot(s->manhole, s->slot);
  const auto& p = std::get<InPipe>(position);
  return spot(p.pipe, p.offset_m);
}

const std::vector<Node>& PositionGraph::extra_spots_in(PipeId pipe) const {
  static const std::vector<Node> kNone;
  auto it = std::lower_bound(spots_by_pipe_.begin(), spots_by_pipe_.end(), pipe,
                             [](const auto& entry, PipeId id) { return entry.first < id; });
  return it == spots_by_pipe_.end() || it->first != pipe ? kNone : it->second;
}

std::optional<PipeId> PositionGraph::pipe_of(Node n) const {
  const Node first_end = manholes_ + slots_;
  const Node first_spot = first_end + 2 * pipes_;
  if (n < first_end) return std::nullopt;
  if (n < first_spot) return PipeId{(n - first_end) / 2};
  return spots_[n - first_spot].pipe;
}

double PositionGraph::offset_of(Node n) const {
  const Node first_end = manholes_ + slots_;
  const Node first_spot = first_end + 2 * pipes_;
  SEWER_CHECK(n >= first_end, "offset of a node that is not in a pipe");
  if (n < first_spot) {
    const PipeId p{(n - first_end) / 2};
    return (n - first_end) % 2 == 0 ? 0.0 : map_.pipe(p).length_m;
  }
  return spots_[n - first_spot].offset_m;
}

RobotPosition PositionGraph::position(Node n) const {
  if (n < manholes_) return InManhole{ManholeId{n}};
  if (n < manholes_ + slots_) {
    SlotIndex s{0};
    const ManholeId m = manhole_of_slot_node(n, &s);
    return AtSlot{m, s};
  }
  return InPipe{*pipe_of(n), offset_of(n)};
}

bool PositionGraph::closed(ManholeId m, SlotIndex from, SlotIndex to) const {
  return std::binary_search(closed_passages_.begin(), closed_passages_.end(),
                            normalised({m, from, to}), passage_less);
}

void PositionGraph::judge_manhole(ManholeId m) const {
  GraphCore& core = *core_;
  const std::uint16_t count = map_.manhole(m).slot_count;
  const std::size_t begin = core.passage_begin[m.index()];
  for (std::uint16_t i = 0; i < count; ++i) {
    for (std::uint16_t j = 0; j < count; ++j) {
      Cost cost = kInfiniteCost;
      if (i != j) {
        const PassageVerdict verdict =
            judge_passage(map_, core.profile, core.motion.get(), m, SlotIndex{i}, SlotIndex{j});
        if (verdict.allowed) cost = to_cost(verdict.duration_s);
      }
      core.passages[begin + std::size_t{i} * count + j] = cost;
    }
  }
  core.judged[m.index()] = true;
}

Cost PositionGraph::drive_cost(double distance_m) const {
  return to_cost(distance_m / profile_.speed_mps);
}

PlanStep PositionGraph::step(Node from, Node to) const {
  const RobotPosition a = position(from);
  const RobotPosition b = position(to);
  if (const auto* m = std::get_if<InManhole>(&a)) {
    return EnterPipe{m->manhole, std::get<InPipe>(b).pipe};
  }
  if (const auto* s = std::get_if<AtSlot>(&a)) {
    const PipeId p = std::get<InPipe>(b).pipe;
    const std::size_t end = *end_in_manhole(map_, p, s->manhole);
    return DriveManhole{s->manhole, s->slot, map_.pipe(p).ends[end].slot};
  }
  return DrivePipeToManhole{std::get<InPipe>(a).pipe, std::get<AtSlot>(b).manhole};
}

}  // namespace sewerplan::domain::detail
