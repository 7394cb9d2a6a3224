// SPDX-License-Identifier: MIT
// Reading plans: the paper's text, FF's numbered steps and Fast Downward's parenthesised actions.
#include <algorithm>
#include <optional>
#include <span>

#include "sewerplan/core/map_queries.h"
#include "sewerplan/domain/plan_text.h"

#include "object_names.h"
#include "plan_lexer.h"

namespace sewerplan::domain {
namespace {

using detail::ascii_upper;
using detail::NameIndex;
using detail::quote_token;

class PlanParser {
 public:
  PlanParser(const SewerMap& map, const Mission& mission, const std::string& file,
             Diagnostics& diagnostics)
      : map_(map),
        mission_(mission),
        file_(file),
        diagnostics_(diagnostics),
        manholes_("manhole", exact_manhole(map), manhole_names(map)),
        pipes_("pipe", exact_pipe(map), pipe_names(map)),
        tasks_("task", exact_task(mission), task_names(mission)) {}

  // Reads one line; a bad line is reported and adds no step.
  void read_line(std::string_view raw, std::size_t number, Plan& plan) {
    where_ = file_ + ":" + std::to_string(number);
    auto text = detail::action_text(raw);
    if (const auto* problem = std::get_if<std::string>(&text)) return error(*problem);
    const std::string_view line = std::get<std::string_view>(text);
    if (line.empty()) return;
    const std::vector<std::string_view> tokens = detail::split(line);
    const std::string action = ascii_upper(tokens.front());
    const std::span<const std::string_view> args(tokens.data() + 1, tokens.size() - 1);
    if (auto step = read_action(action, tokens.front(), args)) plan.steps.push_back(*step);
  }

 private:
  std::optional<PlanStep> read_action(const std::string& action, std::string_view written,
                                      std::span<const std::string_view> args) {
    if (action == "DRIVE_PIPE_TO_MANHOLE" || action == "ENTER_PIPE") {
      if (!arity(action, args, 2, 2, "P M")) return std::nullopt;
      const bool enter = action == "ENTER_PIPE";
      auto pipe = find_pipe(args[enter ? 1 : 0]);
      auto manhole = find_manhole(args[enter ? 0 : 1]);
      if (!pipe || !manhole) return std::nullopt;
      if (enter) return EnterPipe{*manhole, *pipe};
      return DrivePipeToManhole{*pipe, *manhole};
    }
    if (action == "TAKE_WATER_SAMPLE" || action == "GO_TO_POINT") {
      if (!arity(action, args, 1, 2, "P [TASK]")) return std::nullopt;
      const bool sample = action == "TAKE_WATER_SAMPLE";
      auto pipe = find_pipe(args[0]);
      if (!pipe) return std::nullopt;
      const TaskKind kind = sample ? TaskKind::kTakeWaterSample : TaskKind::kGoTo;
      auto task = resolve_task(
          detail::tasks_in_pipe(mission_, kind, *pipe), optional_arg(args, 1),
          std::string(sample ? "water-sample" : "go-to") + " task in pipe " + map_.pipe(*pipe).name,
          action + " " + map_.pipe(*pipe).name);
      if (!task) return std::nullopt;
      if (sample) return TakeWaterSample{*pipe, *task};
      return GoToPoint{*pipe, *task};
    }
    if (action == "GO_TO_MANHOLE") {
      if (!arity(action, args, 1, 2, "M [TASK]")) return std::nullopt;
      auto manhole = find_manhole(args[0]);
      if (!manhole) return std::nullopt;
      const std::string& name = map_.manhole(*manhole).name;
      auto task = resolve_task(detail::go_to_tasks_at(mission_, *manhole), optional_arg(args, 1),
                               "go-to task at manhole " + name, action + " " + name);
      if (!task) return std::nullopt;
      return GoToManhole{*manhole, *task};
    }
    if (action == "INSPECT_PIPE") return read_inspect(args);
    if (action.starts_with(detail::kDriveManholePrefix)) return read_drive_manhole(action, args);
    error("unknown action " + quote_token(written) + " (" + std::string(detail::kActionNames) +
          ")");
    return std::nullopt;
  }

  std::optional<PlanStep> read_inspect(std::span<const std::string_view> args) {
    if (!arity("INSPECT_PIPE", args, 1, 3, "P [M|-] [TASK]")) return std::nullopt;
    auto pipe = find_pipe(args[0]);
    if (!pipe) return std::nullopt;
    InspectPipe step{*pipe, TaskId{0}, std::nullopt};
    std::optional<std::string_view> task_token;
    if (args.size() == 3) {
      step.finish_end = finish_end(*pipe, args[1]);
      if (!step.finish_end) return std::nullopt;
      task_token = args[2];
    } else if (args.size() == 2) {
      // One token: the finish end if it is '-' or a manhole, else a task.
      if (args[1] == "-" || std::holds_alternative<std::uint32_t>(manholes_.find(args[1]))) {
        step.finish_end = finish_end(*pipe, args[1]);
        if (!step.finish_end) return std::nullopt;
      } else {
        task_token = args[1];
      }
    }
    const std::string& name = map_.pipe(*pipe).name;
    auto task = resolve_task(detail::tasks_in_pipe(mission_, TaskKind::kInspectPipe, *pipe),
                             task_token, "inspection of pipe " + name, "INSPECT_PIPE " + name);
    if (!task) return std::nullopt;
    step.task = *task;
    return step;
  }

  // The end of `pipe` that `token` names: a manhole at one of its ends, or '-' for a blind end.
  std::optional<std::uint8_t> finish_end(PipeId pipe, std::string_view token) {
    const Pipe& p = map_.pipe(pipe);
    if (token == "-") {
      const bool blind0 = !p.ends[0].manhole;
      const bool blind1 = !p.ends[1].manhole;
      if (blind0 != blind1) return static_cast<std::uint8_t>(blind0 ? 0 : 1);
      error(blind0 ? "both ends of pipe " + p.name + " are blind: '-' does not say which"
                   : "pipe " + p.name + " has no blind end for '-'");
      return std::nullopt;
    }
    auto manhole = find_manhole(token);
    if (!manhole) return std::nullopt;
    if (auto end = end_in_manhole(map_, pipe, *manhole)) return static_cast<std::uint8_t>(*end);
    error(map_.manhole(*manhole).name + " is not at an end of pipe " + p.name + " (" +
          end_names(p) + ")");
    return std::nullopt;
  }

  std::optional<PlanStep> read_drive_manhole(const std::string& action,
                                             std::span<const std::string_view> args) {
    auto name = detail::read_drive_manhole_name(action);
    if (!name) {
      error("cannot read " + quote_token(action) + " as DRIVE_MANHOLE_TYPE_k[_TYPE_V]_FROM_i_TO_j");
      return std::nullopt;
    }
    if (args.empty()) {
      error(action + " needs the manhole and its pipes in slot order");
      return std::nullopt;
    }
    auto id = find_manhole(args[0]);
    if (!id) return std::nullopt;
    const Manhole& m = map_.manhole(*id);
    if (name->type != m.slot_count || name->variant != m.variant) {
      std::string said = "TYPE_" + std::to_string(name->type);
      if (name->variant) said += std::string("_TYPE_") + *name->variant;
      error(m.name + " is " + detail::paper_type(m) + ", not " + said);
      return std::nullopt;
    }
    for (std::uint32_t slot : {name->from, name->to}) {
      if (slot < 1 || slot > m.slot_count) {
        error("slot " + std::to_string(slot) + " is out of range: " + m.name + " has slots 1 to " +
              std::to_string(m.slot_count));
        return std::nullopt;
      }
    }
    if (name->from == name->to) {
      error("FROM and TO are the same slot " + std::to_string(name->from) + " of " + m.name);
      return std::nullopt;
    }
    std::string expected;
    for (const Slot& slot : map_.slots(*id)) expected += " " + map_.pipe(slot.pipe).name;
    if (args.size() != 1U + m.slot_count) {
      error(action + " takes " + m.name + " and its " + std::to_string(m.slot_count) +
            " pipes in slot order (" + m.name + expected + "), got " +
            std::to_string(args.size() - 1) + " pipes");
      return std::nullopt;
    }
    bool same = true;
    std::string given;
    for (std::size_t i = 1; i < args.size(); ++i) {
      auto pipe = find_pipe(args[i]);
      if (!pipe) return std::nullopt;
      given += " " + map_.pipe(*pipe).name;
      same = same && *pipe == map_.slot(*id, SlotIndex{static_cast<std::uint16_t>(i - 1)}).pipe;
    }
    if (!same) {
      error(m.name + "'s pipes in slot order are" + expected + ", not" + given);
      return std::nullopt;
    }
    return DriveManhole{*id, SlotIndex{static_cast<std::uint16_t>(name->from - 1)},
                        SlotIndex{static_cast<std::uint16_t>(name->to - 1)}};
  }

  // The task an action does: the one named by `token`, or the only candidate.
  std::optional<TaskId> resolve_task(const std::vector<TaskId>& candidates,
                                     std::optional<std::string_view> token, const std::string& what,
                                     const std::string& usage) {
    if (token) {
      auto found = tasks_.find(*token);
      if (const auto* reason = std::get_if<std::string>(&found)) {
        error(*reason);
        return std::nullopt;
      }
      const TaskId id{std::get<std::uint32_t>(found)};
      if (std::find(candidates.begin(), candidates.end(), id) == candidates.end()) {
        error("task '" + mission_.task(id).name + "' is not a " + what);
        return std::nullopt;
      }
      return id;
    }
    if (candidates.size() == 1) return candidates.front();
    if (candidates.empty()) {
      error("the mission has no " + what);
      return std::nullopt;
    }
    std::string names;
    for (TaskId id : candidates) names += (names.empty() ? "" : ", ") + mission_.task(id).name;
    error("the mission has " + std::to_string(candidates.size()) + " tasks (" + names +
          ") that are a " + what + ": name one, as in " + usage + " " +
          mission_.task(candidates.front()).name);
    return std::nullopt;
  }

  bool arity(const std::string& action, std::span<const std::string_view> args, std::size_t min,
             std::size_t max, std::string_view usage) {
    if (args.size() >= min && args.size() <= max) return true;
    error(action + " takes " + std::string(usage) + ", got " + std::to_string(args.size()) +
          (args.size() == 1 ? " argument" : " arguments"));
    return false;
  }

  static std::optional<std::string_view> optional_arg(std::span<const std::string_view> args,
                                                      std::size_t i) {
    if (i < args.size()) return args[i];
    return std::nullopt;
  }

  std::optional<PipeId> find_pipe(std::string_view token) {
    auto found = pipes_.find(token);
    if (const auto* id = std::get_if<std::uint32_t>(&found)) return PipeId{*id};
    error(std::get<std::string>(found));
    return std::nullopt;
  }

  std::optional<ManholeId> find_manhole(std::string_view token) {
    auto found = manholes_.find(token);
    if (const auto* id = std::get_if<std::uint32_t>(&found)) return ManholeId{*id};
    error(std::get<std::string>(found));
    return std::nullopt;
  }

  std::string end_names(const Pipe& p) const {
    auto end = [&](const PipeEnd& e) {
      return e.manhole ? map_.manhole(*e.manhole).name : std::string("blind end");
    };
    return "its ends: " + end(p.ends[0]) + ", " + end(p.ends[1]);
  }

  void error(std::string message) { diagnostics_.error(where_, std::move(message)); }

  static NameIndex::Exact exact_manhole(const SewerMap& map) {
    return [&map](std::string_view s) -> std::optional<std::uint32_t> {
      if (auto id = map.find_manhole(s)) return id->value();
      return std::nullopt;
    };
  }
  static NameIndex::Exact exact_pipe(const SewerMap& map) {
    return [&map](std::string_view s) -> std::optional<std::uint32_t> {
      if (auto id = map.find_pipe(s)) return id->value();
      return std::nullopt;
    };
  }
  static NameIndex::Exact exact_task(const Mission& mission) {
    return [&mission](std::string_view s) -> std::optional<std::uint32_t> {
      for (TaskId id : mission.task_ids()) {
        if (mission.task(id).name == s) return id.value();
      }
      return std::nullopt;
    };
  }
  static NameIndex::All manhole_names(const SewerMap& map) {
    return [&map] {
      std::vector<std::string> names;
      for (const Manhole& m : map.manholes()) names.push_back(m.name);
      return names;
    };
  }
  static NameIndex::All pipe_names(const SewerMap& map) {
    return [&map] {
      std::vector<std::string> names;
      for (const Pipe& p : map.pipes()) names.push_back(p.name);
      return names;
    };
  }
  static NameIndex::All task_names(const Mission& mission) {
    return [&mission] {
      std::vector<std::string> names;
      for (const Task& t : mission.tasks) names.push_back(t.name);
      return names;
    };
  }

  const SewerMap& map_;
  const Mission& mission_;
  const std::string& file_;
  Diagnostics& diagnostics_;
  NameIndex manholes_;
  NameIndex pipes_;
  NameIndex tasks_;
  std::string where_;
};

}  // namespace

Result<Plan> parse_plan(std::string_view text, const std::string& file_name, const SewerMap& map,
                        const Mission& mission, Diagnostics& diagnostics) {
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  PlanParser parser(map, mission, file_name, diagnostics);
  const Diagnostics::Mark before = diagnostics.mark();
  Plan plan;
  std::size_t number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    parser.read_line(line, ++number, plan);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  if (diagnostics.has_errors_since(before)) {
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  return plan;
}

}  // namespace sewerplan::domain
