// SPDX-License-Identifier: MIT
// export_pddl: the sewer domain as typed STRIPS (docs/pddl.md describes the encoding).
#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "sewerplan/domain/pddl.h"

#include "object_names.h"
#include "position_graph.h"

namespace sewerplan::domain {
namespace {

using detail::PositionGraph;

// What every file says first: what the encoding leaves out.
constexpr std::string_view kLimitsComment =
    "; Written by sewerplan (docs/pddl.md). PDDL cannot carry all of the sewer domain:\n"
    ";  - the robot is 'in pipe P', not at an offset in it; costs are those of whole pipes;\n"
    ";  - the battery and its reserve are not expressed: check plans with `sewerplan check`;\n"
    ";  - REACH_EXIT and ALL_OTHER_TASKS_DONE are bookkeeping, not robot actions: import drops\n"
    ";    them (`sewerplan import-plan`).\n"
    "; The robot's limits (pipe diameters, turns, steps) and the mission's closures are compiled\n"
    "; into the static facts fits, can-enter and passage.\n";

// The PDDL type of a manhole: its slot count and variant, as in the paper's action names.
std::string manhole_type(const Manhole& m) {
  std::string type = "manhole-type-" + std::to_string(m.slot_count);
  if (m.variant) type += std::string("-type-") + static_cast<char>(*m.variant - 'A' + 'a');
  return type;
}

enum class Kind { kSample, kInspection, kPoint, kManhole };

struct KindSpec {
  std::string_view pending;  // pending-task predicate
  std::string_view reached;  // done predicate in place mode
  std::string_view place_type;
};

KindSpec spec(Kind kind) {
  switch (kind) {
    case Kind::kSample:
      return {"sample-pending", "sampled", "pipe"};
    case Kind::kInspection:
      return {"inspection-pending", "inspected", "pipe"};
    case Kind::kPoint:
      return {"point-pending", "reached-point", "pipe"};
    case Kind::kManhole:
      return {"manhole-pending", "reached-manhole", "manhole"};
  }
  return {};
}

Kind kind_of(const Task& task) {
  switch (task.kind) {
    case TaskKind::kTakeWaterSample:
      return Kind::kSample;
    case TaskKind::kInspectPipe:
      return Kind::kInspection;
    case TaskKind::kGoTo:
      break;
  }
  return std::holds_alternative<ManholeId>(task.place) ? Kind::kManhole : Kind::kPoint;
}

// A final go-to of a whole pipe or a manhole is reached by being there when the plan ends.
bool ends_by_being_there(const Task& task) {
  if (task.kind != TaskKind::kGoTo) return false;
  if (std::holds_alternative<ManholeId>(task.place)) return true;
  const auto& spot = std::get<PipeSpot>(task.place);
  return !spot.offset_m && !spot.point;
}

class Exporter {
 public:
  Exporter(const SewerMap& map, const Mission& mission, const PddlOptions& options,
           const MissionProgress& progress)
      : map_(map),
        mission_(mission),
        options_(options),
        progress_(progress),
        graph_(map, mission),
        names_(map, mission) {
    for (TaskId t : mission.task_ids()) {
      if (progress.done[t.index()]) continue;
      const Task& task = mission.task(t);
      if (task.final && ends_by_being_there(task)) continue;
      const Kind kind = kind_of(task);
      if (!places_[kind].insert(place_name(task)).second) task_mode_.insert(kind);
      pending_.push_back(t);
    }
    for (const Manhole& m : map.manholes()) max_slots_ = std::max<int>(max_slots_, m.slot_count);
    // The bookkeeping actions' preconditions name the other tasks' done facts, so their objects
    // are constants of the domain.
    const bool bookkeeping = !mission.final_task() || (gated_final() && others_done() != "");
    for (TaskId t : pending_) {
      const Task& task = mission.task(t);
      if (!bookkeeping || task.final) continue;
      constants_.insert(place_name(task));
      if (task_mode(kind_of(task))) constants_.insert(names_.task(t));
    }
  }

  PddlFiles run() {
    PddlFiles files;
    files.domain = domain_text();
    files.problem = problem_text();
    return files;
  }

 private:
  std::string place_name(const Task& task) const {
    if (const auto* m = std::get_if<ManholeId>(&task.place)) return names_.manhole(*m);
    return names_.pipe(std::get<PipeSpot>(task.place).pipe);
  }

  bool task_mode(Kind kind) const { return task_mode_.count(kind) != 0; }
  bool has_kind(Kind kind) const { return places_.count(kind) != 0; }

  // The fact that says task t is done: (sampled P6) or (done t).
  std::string done_fact(TaskId t) const {
    const Task& task = mission_.task(t);
    const Kind kind = kind_of(task);
    if (task_mode(kind)) return "(done " + names_.task(t) + ")";
    return "(" + std::string(spec(kind).reached) + " " + place_name(task) + ")";
  }
  std::string pending_fact(TaskId t) const {
    const Task& task = mission_.task(t);
    const Kind kind = kind_of(task);
    std::string fact = "(" + std::string(spec(kind).pending) + " ";
    if (task_mode(kind)) fact += names_.task(t) + " ";
    return fact + place_name(task) + ")";
  }
  std::optional<TaskId> gated_final() const {
    for (TaskId t : pending_) {
      if (mission_.task(t).final) return t;
    }
    return std::nullopt;
  }
  std::string others_done() const {
    std::string facts;
    for (TaskId t : pending_) {
      if (!mission_.task(t).final) facts += " " + done_fact(t);
    }
    return facts;
  }
  std::string cost(std::string_view amount) const {
    if (!options_.action_costs) return "";
    return " (increase (total-cost) " + std::string(amount) + ")";
  }

  // --- domain ---------------------------------------------------------------------------------

  std::string domain_text() const {
    std::ostringstream out;
    out << kLimitsComment << "(define (domain sewer)\n  (:requirements :strips :typing"
        << (options_.action_costs ? " :action-costs" : "") << ")\n";
    out << "  (:types manhole pipe task - object";
    std::set<std::string> types;
    for (const Manhole& m : map_.manholes()) types.insert(manhole_type(m));
    for (const std::string& t : types) out << "\n          " << t;
    if (!types.empty()) out << " - manhole";
    out << ")\n";
    if (!constants_.empty()) {
      out << "  (:constants";  // the objects the bookkeeping actions name
      write_typed_objects(out, true);
      out << ")\n";
    }
    write_predicates(out);
    if (options_.action_costs) {
      out << "  (:functions (total-cost) - number (drive-cost ?p - pipe) - number\n"
             "              (inspect-cost ?p - pipe) - number\n"
             "              (pass-cost ?m - manhole ?from ?to - pipe) - number)\n";
    }
    write_movement_actions(out);
    write_task_actions(out);
    write_bookkeeping_actions(out);
    out << ")\n";
    return out.str();
  }

  void write_predicates(std::ostream& out) const {
    out << "  (:predicates\n"
           "    (in-manhole ?m - manhole)            ; lowered into ?m, at no pipe mouth\n"
           "    (at ?m - manhole ?p - pipe)          ; in ?m at the mouth of ?p\n"
           "    (at-manhole ?m - manhole)            ; in ?m, at a pipe mouth or not\n"
           "    (in-pipe ?p - pipe)                  ; somewhere in ?p\n"
           "    (fits ?p - pipe)                     ; static: the robot fits ?p's diameter\n"
           "    (pipe-end ?p - pipe ?m - manhole)    ; static: ?p ends in ?m\n"
           "    (can-enter ?m - manhole ?p - pipe)   ; static: ?p ends in ?m and may be entered\n"
           "    (passage ?m - manhole ?from ?to - pipe) ; static: the robot may pass ?m so\n"
           "    (exit ?m - manhole)                  ; static: the robot can be recovered at ?m\n"
           "    (mission-over)                       ; the robot has reached an exit\n";
    for (int k = 1; k <= std::max(max_slots_, 1); ++k) {
      out << "    (slot-" << k << " ?m - manhole ?p - pipe)\n";
    }
    if (!task_mode_.empty()) out << "    (done ?t - task)\n";
    for (Kind kind : {Kind::kSample, Kind::kInspection, Kind::kPoint, Kind::kManhole}) {
      if (!has_kind(kind)) continue;
      const KindSpec s = spec(kind);
      const std::string place = "?x - " + std::string(s.place_type);
      if (task_mode(kind)) {
        out << "    (" << s.pending << " ?t - task " << place << ")\n";
      } else {
        out << "    (" << s.pending << " " << place << ")\n    (" << s.reached << " " << place
            << ")\n";
      }
    }
    out << "  )\n";
  }

  void write_movement_actions(std::ostream& out) const {
    out << "  (:action DRIVE_PIPE_TO_MANHOLE\n"
           "    :parameters (?p - pipe ?m - manhole)\n"
           "    :precondition (and (in-pipe ?p) (fits ?p) (pipe-end ?p ?m))\n"
           "    :effect (and (not (in-pipe ?p)) (at ?m ?p) (at-manhole ?m)"
        << cost("(drive-cost ?p)") << "))\n";
    out << "  (:action ENTER_PIPE\n"
           "    :parameters (?m - manhole ?p - pipe)\n"
           "    :precondition (and (in-manhole ?m) (can-enter ?m ?p))\n"
           "    :effect (and (not (in-manhole ?m)) (not (at-manhole ?m)) (in-pipe ?p)"
        << cost(std::to_string(to_cost(mission_.profile.manhole_pass_s))) << "))\n";
    std::map<std::string, const Manhole*> types;  // one schema family per type
    for (const Manhole& m : map_.manholes()) types.emplace(manhole_type(m), &m);
    for (const auto& entry : types) {
      const Manhole& m = *entry.second;
      for (int i = 1; i <= m.slot_count; ++i) {
        for (int j = 1; j <= m.slot_count; ++j) {
          if (i != j) write_drive_manhole(out, m, entry.first, i, j);
        }
      }
    }
  }

  void write_drive_manhole(std::ostream& out, const Manhole& m, const std::string& type, int i,
                           int j) const {
    out << "  (:action DRIVE_MANHOLE_" << detail::paper_type(m) << "_FROM_" << i << "_TO_" << j
        << "\n    :parameters (?m - " << type;
    for (int k = 1; k <= m.slot_count; ++k) out << " ?p" << k;
    out << " - pipe)\n    :precondition (and";
    for (int k = 1; k <= m.slot_count; ++k) out << " (slot-" << k << " ?m ?p" << k << ")";
    out << "\n                       (at ?m ?p" << i << ") (passage ?m ?p" << i << " ?p" << j
        << "))\n    :effect (and (not (at ?m ?p" << i << ")) (not (at-manhole ?m)) (in-pipe ?p" << j
        << ")" << cost("(pass-cost ?m ?p" + std::to_string(i) + " ?p" + std::to_string(j) + ")")
        << "))\n";
  }

  void write_task_action(std::ostream& out, Kind kind, std::string_view name,
                         std::string_view extra_parameters, std::string_view extra_precondition,
                         std::string_view amount) const {
    const KindSpec s = spec(kind);
    const bool manhole = kind == Kind::kManhole;
    const std::string place = manhole ? "?m" : "?p";
    out << "  (:action " << name << "\n    :parameters (" << place << " - " << s.place_type
        << extra_parameters << (task_mode(kind) ? " ?t - task" : "") << ")\n    :precondition (and "
        << (manhole ? "(at-manhole ?m)" : "(in-pipe ?p) (fits ?p)") << extra_precondition << " ("
        << s.pending << (task_mode(kind) ? " ?t " : " ") << place << "))\n    :effect (and (not ("
        << s.pending << (task_mode(kind) ? " ?t " : " ") << place << ")) "
        << (task_mode(kind) ? "(done ?t)" : "(" + std::string(s.reached) + " " + place + ")")
        << (amount.empty() ? "" : cost(amount)) << "))\n";
  }

  void write_task_actions(std::ostream& out) const {
    if (has_kind(Kind::kSample)) {
      write_task_action(out, Kind::kSample, "TAKE_WATER_SAMPLE", "", "",
                        std::to_string(to_cost(mission_.profile.sample_s)));
    }
    if (has_kind(Kind::kInspection)) {
      // ?m is the manhole at which the inspection finishes (the paper's INSPECT_PIPE P4, with
      // the finish end written out because the robot's offset in the pipe is not modelled).
      write_task_action(out, Kind::kInspection, "INSPECT_PIPE", " ?m - manhole",
                        " (pipe-end ?p ?m)", "(inspect-cost ?p)");
    }
    if (has_kind(Kind::kPoint)) write_task_action(out, Kind::kPoint, "GO_TO_POINT", "", "", "");
    if (has_kind(Kind::kManhole)) {
      write_task_action(out, Kind::kManhole, "GO_TO_MANHOLE", "", "", "");
    }
  }

  void write_bookkeeping_actions(std::ostream& out) const {
    if (const auto final_task = gated_final(); final_task && others_done() != "") {
      out << "  (:action ALL_OTHER_TASKS_DONE ; bookkeeping: the final task may be done now\n"
             "    :parameters ()\n    :precondition (and"
          << others_done() << ")\n    :effect " << pending_fact(*final_task) << ")\n";
    }
    if (!mission_.final_task()) {
      out << "  (:action REACH_EXIT ; bookkeeping: the mission ends at an exit\n"
             "    :parameters (?m - manhole)\n    :precondition (and (at-manhole ?m) (exit ?m)"
          << others_done() << ")\n    :effect (mission-over))\n";
    }
  }

  // --- problem --------------------------------------------------------------------------------

  std::string problem_text() const {
    std::ostringstream out;
    out << kLimitsComment;
    out << "; map '" << map_.name() << "', mission '" << mission_.name << "', robot profile '"
        << mission_.profile.name << "'\n";
    write_renames(out);
    out << "(define (problem mission)\n  (:domain sewer)\n  (:objects";
    write_typed_objects(out, false);
    out << ")\n  (:init\n";
    write_position(out);
    write_static_facts(out);
    write_task_facts(out);
    if (options_.action_costs) write_cost_facts(out);
    out << "  )\n  (:goal (and";
    write_goal(out);
    out << "))\n";
    if (options_.action_costs) out << "  (:metric minimize (total-cost))\n";
    out << ")\n";
    return out.str();
  }

  void write_renames(std::ostream& out) const {
    if (names_.renamed_count() == 0) return;
    out << "; " << names_.renamed_count() << " object(s) renamed to be PDDL names:\n";
    auto note = [&](std::string_view kind, const std::string& pddl, const std::string& original) {
      if (pddl != original) out << ";   " << kind << " '" << original << "' is " << pddl << '\n';
    };
    for (ManholeId m : map_.manhole_ids()) note("manhole", names_.manhole(m), map_.manhole(m).name);
    for (PipeId p : map_.pipe_ids()) note("pipe", names_.pipe(p), map_.pipe(p).name);
    for (TaskId t : mission_.task_ids()) note("task", names_.task(t), mission_.task(t).name);
  }

  // The objects, by type: the domain's constants (`constants`) or the problem's other objects.
  void write_typed_objects(std::ostream& out, bool constants) const {
    std::map<std::string, std::vector<std::string>> by_type;
    auto add = [&](const std::string& name, const std::string& type) {
      if ((constants_.count(name) != 0) == constants) by_type[type].push_back(name);
    };
    for (ManholeId m : map_.manhole_ids()) add(names_.manhole(m), manhole_type(map_.manhole(m)));
    for (PipeId p : map_.pipe_ids()) add(names_.pipe(p), "pipe");
    for (TaskId t : pending_) {
      if (task_mode(kind_of(mission_.task(t)))) add(names_.task(t), "task");
    }
    for (const auto& [type, names] : by_type) {
      for (std::size_t i = 0; i < names.size(); ++i) {
        out << (i % 12 == 0 ? "\n    " : " ") << names[i];
      }
      out << " - " << type;
    }
  }

  void write_position(std::ostream& out) const {
    out << "    ; the robot: " << describe(progress_.position, map_) << '\n';
    if (const auto* in = std::get_if<InManhole>(&progress_.position)) {
      const std::string& m = names_.manhole(in->manhole);
      out << "    (in-manhole " << m << ") (at-manhole " << m << ")\n";
    } else if (const auto* at = std::get_if<AtSlot>(&progress_.position)) {
      const std::string& m = names_.manhole(at->manhole);
      const PipeId p = map_.slots(at->manhole)[at->slot.index()].pipe;
      out << "    (at " << m << " " << names_.pipe(p) << ") (at-manhole " << m << ")\n";
    } else {
      out << "    (in-pipe " << names_.pipe(std::get<InPipe>(progress_.position).pipe) << ")\n";
    }
  }

  void write_static_facts(std::ostream& out) const {
    for (PipeId p : map_.pipe_ids()) {
      const std::string& pipe = names_.pipe(p);
      if (graph_.pipe_fits(p)) out << "    (fits " << pipe << ")\n";
      for (const PipeEnd& end : map_.pipe(p).ends) {
        if (!end.manhole) continue;
        const std::string& m = names_.manhole(*end.manhole);
        out << "    (pipe-end " << pipe << " " << m << ")";
        if (graph_.pipe_drivable(p)) out << " (can-enter " << m << " " << pipe << ")";
        out << '\n';
      }
    }
    for (ManholeId m : map_.manhole_ids()) {
      const std::string& manhole = names_.manhole(m);
      const auto slots = map_.slots(m);
      for (std::size_t i = 0; i < slots.size(); ++i) {
        out << "    (slot-" << i + 1 << " " << manhole << " " << names_.pipe(slots[i].pipe)
            << ")\n";
      }
      for_each_passage(m, [&](SlotIndex i, SlotIndex j) {
        out << "    (passage " << manhole << " " << names_.pipe(slots[i.index()].pipe) << " "
            << names_.pipe(slots[j.index()].pipe) << ")\n";
      });
    }
    for (ManholeId m : mission_.exits) out << "    (exit " << names_.manhole(m) << ")\n";
  }

  template <class F>
  void for_each_passage(ManholeId m, F&& f) const {
    const auto count = static_cast<std::uint16_t>(map_.slots(m).size());
    for (std::uint16_t i = 0; i < count; ++i) {
      for (std::uint16_t j = 0; j < count; ++j) {
        if (i != j && graph_.passage_allowed(m, SlotIndex{i}, SlotIndex{j})) {
          f(SlotIndex{i}, SlotIndex{j});
        }
      }
    }
  }

  void write_task_facts(std::ostream& out) const {
    const auto final_task = gated_final();
    for (TaskId t : pending_) {
      // A gated final task becomes pending through ALL_OTHER_TASKS_DONE, unless it is alone.
      if (final_task && t == *final_task && others_done() != "") continue;
      out << "    " << pending_fact(t) << " ; task " << mission_.task(t).name << '\n';
    }
  }

  void write_cost_facts(std::ostream& out) const {
    out << "    (= (total-cost) 0)\n";
    const RobotProfile& profile = mission_.profile;
    for (PipeId p : map_.pipe_ids()) {
      const Pipe& pipe = map_.pipe(p);
      out << "    (= (drive-cost " << names_.pipe(p) << ") "
          << to_cost(pipe.length_m / profile.speed_mps) << ") (= (inspect-cost " << names_.pipe(p)
          << ") " << to_cost(pipe.length_m / profile.inspection_speed_mps) << ")\n";
    }
    for (ManholeId m : map_.manhole_ids()) {
      const auto slots = map_.slots(m);
      for_each_passage(m, [&](SlotIndex i, SlotIndex j) {
        out << "    (= (pass-cost " << names_.manhole(m) << " "
            << names_.pipe(slots[i.index()].pipe) << " " << names_.pipe(slots[j.index()].pipe)
            << ") " << graph_.passage_cost(m, i, j) << ")\n";
      });
    }
  }

  void write_goal(std::ostream& out) const {
    for (TaskId t : pending_) out << " " << done_fact(t);
    const Task* final_task = mission_.final_task();
    if (!final_task) {
      out << " (mission-over)";
    } else if (ends_by_being_there(*final_task)) {
      if (const auto* m = std::get_if<ManholeId>(&final_task->place)) {
        out << " (at-manhole " << names_.manhole(*m) << ")";
      } else {
        out << " (in-pipe " << names_.pipe(std::get<PipeSpot>(final_task->place).pipe) << ")";
      }
    }
  }

  const SewerMap& map_;
  const Mission& mission_;
  const PddlOptions& options_;
  const MissionProgress& progress_;
  PositionGraph graph_;
  PddlNames names_;
  std::vector<TaskId> pending_;  // tasks to do, in mission order (not a final one reached by
                                 // being there)
  std::map<Kind, std::set<std::string>> places_;  // per kind, the places of its tasks
  std::set<Kind> task_mode_;         // kinds with two tasks at one place: actions name the task
  std::set<std::string> constants_;  // objects the domain names (PDDL names)
  int max_slots_ = 0;
};

}  // namespace

Result<PddlFiles> export_pddl(const SewerMap& map, const Mission& mission,
                              const PddlOptions& options,
                              const std::optional<MissionProgress>& progress) {
  const MissionProgress start = progress ? *progress : initial_progress(mission, map);
  if (start.done.size() != mission.tasks.size()) {
    return Error{ErrorCode::kInvalidArgument,
                 "the progress has " + std::to_string(start.done.size()) +
                     " task flags, the mission " + std::to_string(mission.tasks.size()) + " tasks"};
  }
  return Exporter(map, mission, options, start).run();
}

std::optional<PddlPlanFormat> pddl_plan_format_from_name(std::string_view name) {
  if (name == "ff") return PddlPlanFormat::kFf;
  if (name == "fd" || name == "fast-downward") return PddlPlanFormat::kFastDownward;
  return std::nullopt;
}

}  // namespace sewerplan::domain
