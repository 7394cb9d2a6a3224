// SPDX-License-Identifier: MIT
// The Python module: plan, check and the Replanner.
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sewerplan/core/overloaded.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"
#include "sewerplan/fusion/action_text.h"
#include "sewerplan/fusion/fuse.h"
#include "sewerplan/search/planner.h"

#include "bindings.h"
#include <pybind11/stl.h>

namespace sewerplan::python {
namespace {

using Decision = executor::PlanResponse::Decision;

// One plan step as Python sees it: the paper's text and the objects it names.
struct Step {
  std::string kind;  // domain::step_kind
  std::string text;  // "DRIVE_PIPE_TO_MANHOLE P12 M2"
  std::optional<std::string> pipe;
  std::optional<std::string> manhole;
  std::optional<std::string> task;
};

// One fused action: what the robot is asked to do for a step, with its parameters.
struct Action {
  std::string kind;  // fusion::action_kind
  std::size_t step = 0;
  double duration_s = 0;
  std::string description;  // fusion::describe, with the map's names
};

struct Dropped {
  std::string task;
  std::string reason;
};

// plan()'s answer: the plan and what it cost and took.
struct Outcome {
  std::shared_ptr<PlanHandle> plan;
  double cost_s = 0;
  double energy_wh = 0;
  bool optimal = false;
  std::string algorithm;
  std::size_t improvements = 0;
  std::vector<Dropped> dropped;
  search::SearchStatistics search;
  double risk_cost_s = 0;
};

struct Response {
  Decision decision = Decision::kFollowPlan;
  std::shared_ptr<PlanHandle> plan;
  std::vector<std::string> goals;
  std::vector<Dropped> newly_dropped;
  std::string end;
  std::string reason;
  double planning_time_s = 0;
  double cost_s = 0;
  double energy_wh = 0;
};

// The Replanner with the mission (and so the map) it refers to.
struct ReplannerHandle {
  std::shared_ptr<const MissionHandle> mission;
  std::unique_ptr<executor::Replanner> replanner;
};

std::vector<Dropped> dropped_of(const std::vector<domain::DroppedTask>& tasks,
                                const Mission& mission) {
  std::vector<Dropped> out;
  for (const domain::DroppedTask& d : tasks) out.push_back({mission.task(d.task).name, d.reason});
  return out;
}

Step step_of(const domain::PlanStep& step, const SewerMap& map, const Mission& mission) {
  Step s{std::string(domain::step_kind(step)), domain::format_step(step, map, mission), {}, {}, {}};
  const auto pipe = [&](PipeId id) { s.pipe = map.pipe(id).name; };
  const auto manhole = [&](ManholeId id) { s.manhole = map.manhole(id).name; };
  const auto task = [&](TaskId id) { s.task = mission.task(id).name; };
  std::visit(Overloaded{[&](const domain::DrivePipeToManhole& a) {
                          pipe(a.pipe);
                          manhole(a.manhole);
                        },
                        [&](const domain::DriveManhole& a) { manhole(a.manhole); },
                        [&](const domain::EnterPipe& a) {
                          pipe(a.pipe);
                          manhole(a.manhole);
                        },
                        [&](const domain::TakeWaterSample& a) {
                          pipe(a.pipe);
                          task(a.task);
                        },
                        [&](const domain::InspectPipe& a) {
                          pipe(a.pipe);
                          task(a.task);
                        },
                        [&](const domain::GoToPoint& a) {
                          pipe(a.pipe);
                          task(a.task);
                        },
                        [&](const domain::GoToManhole& a) {
                          manhole(a.manhole);
                          task(a.task);
                        }},
             step);
  return s;
}

std::vector<Step> steps_of(const PlanHandle& h) {
  std::vector<Step> steps;
  for (const domain::PlanStep& s : h.plan.steps) {
    steps.push_back(step_of(s, *h.mission->map, h.mission->mission));
  }
  return steps;
}

std::vector<Action> actions_of(const PlanHandle& h) {
  const SewerMap& map = *h.mission->map;
  const Mission& mission = h.mission->mission;
  Result<fusion::FusedPlan> fused =
      fusion::fuse(h.plan, map, mission, h.start, {.start_heading_end = h.start_heading_end});
  std::vector<Action> actions;
  for (const fusion::RobotAction& a : value_or_raise(std::move(fused)).actions) {
    actions.push_back({std::string(fusion::action_kind(a)), fusion::plan_step(a),
                       fusion::duration_s(a), fusion::describe(a, map, mission)});
  }
  return actions;
}

search::PlannerOptions planner_options(const std::string& algorithm, double time_limit_s,
                                       bool select_goals, std::uint64_t improvement_expansions,
                                       const CancelToken* cancel) {
  search::PlannerOptions options;
  const std::optional<search::Algorithm> a = search::algorithm_from_string(algorithm);
  if (!a) {
    raise_error({ErrorCode::kInvalidArgument,
                 "unknown algorithm '" + algorithm + "' (" + search::algorithm_names() + ")"});
  }
  options.algorithm = *a;
  options.time_limit_s = time_limit_s;
  options.select_goals = select_goals;
  options.improvement_expansions = improvement_expansions;
  if (cancel != nullptr) options.cancel = &cancel->flag();
  return options;
}

Outcome plan(const std::shared_ptr<const MissionHandle>& mission, const std::string& algorithm,
             double time_limit_s, bool select_goals, std::uint64_t improvement_expansions,
             CancelToken* cancel) {
  const search::PlannerOptions options =
      planner_options(algorithm, time_limit_s, select_goals, improvement_expansions, cancel);
  const domain::MissionProgress start = domain::initial_progress(mission->mission, *mission->map);
  std::optional<Result<search::PlanOutcome>> result;
  {
    py::gil_scoped_release release;
    if (cancel != nullptr) cancel->mark_entered();
    result = search::plan_mission(*mission->map, mission->mission, start, options);
  }
  search::PlanOutcome o = value_or_raise(std::move(*result));
  Outcome out;
  out.plan = std::make_shared<PlanHandle>(PlanHandle{mission, std::move(o.plan), start, 1});
  out.cost_s = o.cost_s;
  out.energy_wh = o.energy_wh;
  out.optimal = o.optimal;
  out.algorithm = o.algorithm;
  out.improvements = o.improvements;
  out.dropped = dropped_of(o.dropped, mission->mission);
  out.search = o.search;
  out.risk_cost_s = o.risk_cost_s;
  return out;
}

Response response_of(executor::PlanResponse r, const ReplannerHandle& h) {
  const executor::Replanner& replanner = *h.replanner;
  // The Replanner's mission may have changed (what it learnt): the plan is read against it.
  auto mission =
      std::make_shared<MissionHandle>(MissionHandle{h.mission->map, replanner.mission()});
  Response out;
  out.decision = r.decision;
  out.plan = std::make_shared<PlanHandle>(
      PlanHandle{mission, std::move(r.plan), replanner.progress(), replanner.heading_end()});
  for (TaskId t : r.goals) out.goals.push_back(replanner.mission().task(t).name);
  out.newly_dropped = dropped_of(r.newly_dropped, replanner.mission());
  out.end = r.end;
  out.reason = r.reason;
  out.planning_time_s = r.planning_time_s;
  out.cost_s = r.cost_s;
  out.energy_wh = r.energy_wh;
  return out;
}

std::vector<std::string> done_of(const ReplannerHandle& h) {
  std::vector<std::string> names;
  const Mission& mission = h.replanner->mission();
  for (TaskId t : mission.task_ids()) {
    if (h.replanner->progress().done[t.value()]) names.push_back(mission.task(t).name);
  }
  return names;
}

// Sets `position` in place (a variant returned by value trips GCC 12's -Wmaybe-uninitialized).
void set_position(domain::RobotPosition& position, const SewerMap& map,
                  const std::optional<std::string>& manhole, const std::optional<int>& slot,
                  const std::optional<std::string>& pipe, const std::optional<double>& offset_m) {
  if (manhole.has_value() == pipe.has_value()) {
    raise_error(
        {ErrorCode::kInvalidArgument, "give either manhole (and slot) or pipe and offset_m"});
  }
  if (pipe) {
    position.emplace<domain::InPipe>(pipe_named(map, *pipe), offset_m.value_or(0.0));
    return;
  }
  const ManholeId m = manhole_named(map, *manhole);
  if (!slot) {
    position.emplace<domain::InManhole>(m);
    return;
  }
  if (*slot < 0 || *slot >= map.manhole(m).slot_count) {
    raise_error({ErrorCode::kInvalidArgument,
                 "manhole " + *manhole + " has no slot " + std::to_string(*slot)});
  }
  position.emplace<domain::AtSlot>(m, SlotIndex{static_cast<std::uint16_t>(*slot)});
}

void bind_plan_types(py::module_& m) {
  py::class_<Step>(m, "Step", "One plan step in the paper's actions.")
      .def_readonly("kind", &Step::kind, "As the plan JSON names it: 'drive_pipe_to_manhole', ...")
      .def_readonly("text", &Step::text, "In the paper's form: 'DRIVE_PIPE_TO_MANHOLE P12 M2'.")
      .def_readonly("pipe", &Step::pipe, "The pipe it names, or None.")
      .def_readonly("manhole", &Step::manhole, "The manhole it names, or None.")
      .def_readonly("task", &Step::task, "The task it does, or None.")
      .def("__str__", [](const Step& s) { return s.text; })
      .def("__repr__", [](const Step& s) { return "<Step " + s.text + ">"; });
  py::class_<Action>(m, "Action", "One fused action: a step with its parameters resolved.")
      .def_readonly("kind", &Action::kind, "The action's kind: 'drive_to_manhole', ...")
      .def_readonly("step", &Action::step, "The plan step it does (from 0).")
      .def_readonly("duration_s", &Action::duration_s, "Its expected time (s).")
      .def_readonly("description", &Action::description, "Every parameter, by the map's names.")
      .def("__repr__", [](const Action& a) {
        return Repr("Action")
            .word(a.description)
            .field("step", a.step)
            .field("duration_s", a.duration_s)
            .str();
      });
  py::class_<Dropped>(m, "DroppedTask", "A task left out, and why.")
      .def_readonly("task", &Dropped::task, "The task's name.")
      .def_readonly("reason", &Dropped::reason, "Why: what is out of reach.")
      .def("__repr__",
           [](const Dropped& d) { return "<DroppedTask " + d.task + ": " + d.reason + ">"; });
  py::class_<PlanHandle, std::shared_ptr<PlanHandle>>(
      m, "Plan",
      "A plan in the paper's actions: a sequence of Step (len, indexing from 0, negative indices "
      "and slices, iteration), with its mission.")
      .def_property_readonly(
          "mission", [](const PlanHandle& h) { return h.mission; }, "The Mission it is for.")
      .def_property_readonly("steps", &steps_of, "Every Step, in order (a list).")
      .def_property_readonly("actions", &actions_of, "The fused actions, one per step (fusion).")
      .def_property_readonly(
          "text",
          [](const PlanHandle& h) {
            return domain::format_plan(h.plan, *h.mission->map, h.mission->mission);
          },
          "The plan file: one step a line in the paper's form.")
      .def(
          "__len__", [](const PlanHandle& h) { return h.plan.steps.size(); }, "How many steps.")
      .def(
          "__getitem__",
          [](const PlanHandle& h, std::ptrdiff_t index) {
            const auto size = static_cast<std::ptrdiff_t>(h.plan.steps.size());
            const std::ptrdiff_t i = index < 0 ? index + size : index;
            if (i < 0 || i >= size) {
              throw py::index_error("plan step " + std::to_string(index) + " out of range (" +
                                    std::to_string(size) + " steps)");
            }
            return step_of(h.plan.steps[static_cast<std::size_t>(i)], *h.mission->map,
                           h.mission->mission);
          },
          py::arg("index"), "The Step at index (from 0; negative from the end).")
      .def(
          "__getitem__",
          [](const PlanHandle& h, const py::slice& slice) {
            const std::vector<Step> steps = steps_of(h);
            py::ssize_t start = 0;
            py::ssize_t stop = 0;
            py::ssize_t step = 0;
            py::ssize_t length = 0;
            if (!slice.compute(static_cast<py::ssize_t>(steps.size()), &start, &stop, &step,
                               &length)) {
              throw py::error_already_set();
            }
            std::vector<Step> out;
            for (py::ssize_t i = 0; i < length; ++i) {
              out.push_back(steps[static_cast<std::size_t>(start + i * step)]);
            }
            return out;
          },
          py::arg("index"), "The Steps of a slice, as a list.")
      .def(
          "__iter__", [](const PlanHandle& h) { return py::iter(py::cast(steps_of(h))); },
          "Iterates over the Steps.")
      .def("__str__",
           [](const PlanHandle& h) {
             return domain::format_plan(h.plan, *h.mission->map, h.mission->mission);
           })
      .def("__repr__", [](const PlanHandle& h) {
        Repr repr("Plan");
        repr.field("mission", h.mission->mission.name).field("steps", h.plan.steps.size());
        if (!h.plan.steps.empty()) {
          repr.field("first", domain::format_step(h.plan.steps.front(), *h.mission->map,
                                                  h.mission->mission));
        }
        return repr.str();
      });
  py::class_<search::SearchStatistics>(m, "SearchStatistics", "What a search did.")
      .def_readonly("expanded", &search::SearchStatistics::expanded, "States expanded.")
      .def_readonly("generated", &search::SearchStatistics::generated, "Successors generated.")
      .def_readonly("evaluated", &search::SearchStatistics::evaluated, "Heuristic evaluations.")
      .def_readonly("stored", &search::SearchStatistics::stored, "Distinct states stored.")
      .def_readonly("time_s", &search::SearchStatistics::time_s, "Search time (s, wall clock).")
      .def("__repr__", [](const search::SearchStatistics& st) {
        return Repr("SearchStatistics")
            .field("expanded", st.expanded)
            .field("generated", st.generated)
            .field("evaluated", st.evaluated)
            .field("stored", st.stored)
            .field("time_s", st.time_s)
            .str();
      });
  py::class_<Outcome>(m, "PlanOutcome", "plan()'s answer: the plan and what it costs.")
      .def_readonly("plan", &Outcome::plan, "The Plan.")
      .def_readonly("cost_s", &Outcome::cost_s, "The plan's time (s).")
      .def_readonly("energy_wh", &Outcome::energy_wh, "The plan's energy (Wh).")
      .def_readonly("optimal", &Outcome::optimal, "Whether the search proved it the cheapest.")
      .def_readonly("algorithm", &Outcome::algorithm, "The algorithm that found it.")
      .def_readonly("improvements", &Outcome::improvements,
                    "How often the anytime search improved on its first plan.")
      .def_readonly("dropped", &Outcome::dropped, "With select_goals: the DroppedTask list.")
      .def_readonly("statistics", &Outcome::search, "The SearchStatistics.")
      .def_readonly("risk_cost_s", &Outcome::risk_cost_s,
                    "The expected time lost to the map's findings (s; risk-aware planning).")
      .def("__repr__", [](const Outcome& o) {
        Repr repr("PlanOutcome");
        repr.field("steps", o.plan->plan.steps.size())
            .field("cost_s", o.cost_s)
            .field("energy_wh", o.energy_wh)
            .field("optimal", o.optimal)
            .field("algorithm", o.algorithm);
        if (!o.dropped.empty()) repr.field("dropped", o.dropped.size());
        return repr.str();
      });
  py::class_<domain::ValidationReport>(m, "ValidationReport",
                                       "check()'s answer; true when the plan is valid.")
      .def_readonly("valid", &domain::ValidationReport::valid,
                    "Whether every step runs and every task is done.")
      .def_readonly("failed_step", &domain::ValidationReport::failed_step,
                    "The first step that cannot run (from 0), or None.")
      .def_readonly("error", &domain::ValidationReport::error,
                    "Why the plan is invalid (steps numbered from 1); empty when valid.")
      .def_readonly("step_costs_s", &domain::ValidationReport::step_costs_s,
                    "The time of each step run (s).")
      .def_readonly("total_cost_s", &domain::ValidationReport::total_cost_s, "Their sum (s).")
      .def_readonly("energy_wh", &domain::ValidationReport::energy_wh,
                    "The energy of the steps run (Wh).")
      .def(
          "__bool__", [](const domain::ValidationReport& r) { return r.valid; }, "valid.")
      .def("__str__",
           [](const domain::ValidationReport& r) {
             std::ostringstream out;
             out << r;
             return out.str();
           })
      .def("__repr__", [](const domain::ValidationReport& r) {
        Repr repr("ValidationReport");
        repr.field("valid", r.valid).field("total_cost_s", r.total_cost_s);
        if (!r.valid) repr.field("failed_step", r.failed_step).field("error", r.error);
        return repr.str();
      });
}

void bind_plan_functions(py::module_& m) {
  m.def("plan", &plan, py::arg("mission"), py::arg("algorithm") = "auto",
        py::arg("time_limit_s") = 0.0, py::arg("select_goals") = false,
        py::arg("improvement_expansions") = 10'000, py::arg("cancel") = nullptr,
        "Plans the mission from its start; a PlanOutcome. algorithm: 'auto', 'ehc', 'gbfs', "
        "'wastar', 'astar', 'exact'; time_limit_s: wall-clock seconds (0: none); select_goals: "
        "leave out the tasks out of reach; improvement_expansions: the anytime search's budget "
        "after its first plan (states); cancel: a CancelToken. The GIL is released meanwhile. "
        "Raises NoPlanError (the message lists the reasons), SearchLimitError, CancelledError.");
  m.def(
      "parse_plan",
      [](std::shared_ptr<const MissionHandle> mission, const std::string& text,
         const std::string& file_name) {
        Diagnostics diagnostics;
        domain::Plan p = value_or_raise(
            domain::parse_plan(text, file_name, *mission->map, mission->mission, diagnostics),
            &diagnostics);
        const domain::MissionProgress start =
            domain::initial_progress(mission->mission, *mission->map);
        return std::make_shared<PlanHandle>(PlanHandle{std::move(mission), std::move(p), start, 1});
      },
      py::arg("mission"), py::arg("text"), py::arg("file_name") = "<string>",
      "Reads a plan in the paper's text form (ours, FF's or Fast Downward's) for the mission; a "
      "bad line raises ParseError with a diagnostic naming file_name and the line.");
  m.def(
      "check",
      [](const PlanHandle& plan) {
        return domain::validate_plan(plan.plan, *plan.mission->map, plan.mission->mission,
                                     plan.start);
      },
      py::arg("plan"),
      "Replays the plan from its start against its map and mission (the validator); a "
      "ValidationReport.");
}

void bind_replanner(py::module_& m) {
  py::enum_<Decision>(m, "Decision", "The Replanner's answer: what the robot does with it.")
      .value("FOLLOW_PLAN", Decision::kFollowPlan)
      .value("DEGRADED", Decision::kDegraded)
      .value("EXIT_ON_RESERVE", Decision::kExitOnReserve)
      .value("CALL_FOR_RECOVERY", Decision::kCallForRecovery)
      .value("STUCK", Decision::kStuck)
      .value("INVALID_REPORT", Decision::kInvalidReport)
      .def_property_readonly(
          "label", [](Decision d) { return std::string(executor::to_string(d)); },
          "The stable name: 'follow-plan', 'degraded', ...");
  py::enum_<executor::Failure::Kind>(m, "FailureKind",
                                     "What the robot met that its recovery could not clear.")
      .value("BLOCKAGE", executor::Failure::Kind::kBlockage)
      .value("DANGER_IN_PIPE", executor::Failure::Kind::kDangerInPipe)
      .value("DANGEROUS_PASSAGE", executor::Failure::Kind::kDangerousPassage)
      .value("STUCK", executor::Failure::Kind::kStuck);
  py::class_<Response>(m, "PlanResponse", "The Replanner's answer.")
      .def_readonly("decision", &Response::decision, "The Decision.")
      .def_readonly("plan", &Response::plan, "The Plan from where the robot is.")
      .def_readonly("goals", &Response::goals, "The tasks the plan does.")
      .def_readonly("newly_dropped", &Response::newly_dropped,
                    "The tasks this answer left out (DroppedTask).")
      .def_readonly("end", &Response::end, "Where the plan ends: the exit manhole's name.")
      .def_readonly("reason", &Response::reason, "Why it planned: 'start', a failure, ...")
      .def_readonly("planning_time_s", &Response::planning_time_s, "Planning time (s).")
      .def_readonly("cost_s", &Response::cost_s, "The plan's time (s).")
      .def_readonly("energy_wh", &Response::energy_wh, "The plan's energy (Wh).")
      .def_property_readonly(
          "has_plan", [](const Response& r) { return executor::has_plan(r.decision); },
          "Whether the robot has a plan to follow.")
      .def_property_readonly(
          "calls_beacon", [](const Response& r) { return executor::calls_beacon(r.decision); },
          "Whether the robot calls for recovery (CALL_FOR_RECOVERY, STUCK).")
      .def("__repr__", [](const Response& r) {
        Repr repr("PlanResponse");
        repr.field("decision", std::string(executor::to_string(r.decision)))
            .field("steps", r.plan->plan.steps.size())
            .field("cost_s", r.cost_s)
            .field("end", r.end);
        if (!r.newly_dropped.empty()) repr.field("newly_dropped", r.newly_dropped.size());
        return repr.str();
      });
  py::class_<ReplannerHandle>(m, "Replanner",
                              "The planning system robot software embeds (executor/replanner.h).")
      .def(py::init([](std::shared_ptr<const MissionHandle> mission, double time_limit_s) {
             executor::ReplannerOptions options;
             options.planner.time_limit_s = time_limit_s;
             auto replanner =
                 std::make_unique<executor::Replanner>(*mission->map, mission->mission, options);
             return ReplannerHandle{std::move(mission), std::move(replanner)};
           }),
           py::arg("mission"), py::arg("time_limit_s") = 0.0,
           "A Replanner for the mission; time_limit_s: each plan's time limit (s, 0: none).")
      .def(
          "plan",
          [](ReplannerHandle& h, const std::string& reason) {
            std::optional<executor::PlanResponse> r;
            {
              py::gil_scoped_release release;
              r = h.replanner->plan(reason);
            }
            return response_of(std::move(*r), h);
          },
          py::arg("reason") = "start",
          "Plans from where the robot is (the GIL is released meanwhile); a PlanResponse.")
      .def(
          "update",
          [](ReplannerHandle& h, const std::optional<std::string>& manhole,
             const std::optional<int>& slot, const std::optional<std::string>& pipe,
             const std::optional<double>& offset_m, const std::vector<std::string>& done,
             double energy_used_wh, int heading_end) {
            const SewerMap& map = *h.mission->map;
            const Mission& mission = h.replanner->mission();
            domain::MissionProgress progress;
            set_position(progress.position, map, manhole, slot, pipe, offset_m);
            progress.done = h.replanner->progress().done;
            for (const std::string& name : done) {
              bool found = false;
              for (TaskId t : mission.task_ids()) {
                if (mission.task(t).name == name) {
                  progress.done[t.value()] = true;
                  found = true;
                }
              }
              if (!found) raise_error({ErrorCode::kInvalidArgument, "no task '" + name + "'"});
            }
            progress.energy_used_wh = energy_used_wh;
            if (heading_end != 0 && heading_end != 1) {
              raise_error({ErrorCode::kInvalidArgument, "heading_end must be 0 or 1"});
            }
            const Result<void> updated =
                h.replanner->update(progress, static_cast<std::uint8_t>(heading_end));
            if (!updated.has_value()) raise_error(updated.error());
          },
          py::kw_only(), py::arg("manhole") = py::none(), py::arg("slot") = py::none(),
          py::arg("pipe") = py::none(), py::arg("offset_m") = py::none(),
          py::arg("done") = std::vector<std::string>{}, py::arg("energy_used_wh") = 0.0,
          py::arg("heading_end") = 1,
          "Where the robot is (a manhole, a manhole's slot from 0, or a pipe and offset), the "
          "tasks it has done since, and the energy used; heading_end: the end of its pipe it "
          "faces.")
      .def(
          "report_failure",
          [](ReplannerHandle& h, executor::Failure::Kind kind,
             const std::optional<std::string>& pipe, double offset_m,
             const std::optional<std::string>& manhole, int from_slot, int to_slot,
             const std::string& detail) {
            const SewerMap& map = *h.mission->map;
            executor::Failure failure{.kind = kind, .offset_m = offset_m, .detail = detail};
            if (pipe) failure.pipe = pipe_named(map, *pipe);
            if (manhole) failure.manhole = manhole_named(map, *manhole);
            if (from_slot < 0 || to_slot < 0 || from_slot > 0xffff || to_slot > 0xffff) {
              raise_error({ErrorCode::kInvalidArgument, "slots are numbered from 0"});
            }
            failure.from = SlotIndex{static_cast<std::uint16_t>(from_slot)};
            failure.to = SlotIndex{static_cast<std::uint16_t>(to_slot)};
            std::optional<executor::PlanResponse> r;
            {
              py::gil_scoped_release release;
              r = h.replanner->report_failure(failure);
            }
            return response_of(std::move(*r), h);
          },
          py::arg("kind"), py::kw_only(), py::arg("pipe") = py::none(), py::arg("offset_m") = 0.0,
          py::arg("manhole") = py::none(), py::arg("from_slot") = 0, py::arg("to_slot") = 0,
          py::arg("detail") = "",
          "What the robot met that its recovery could not clear; the world model changes and "
          "the Replanner plans again (a bad report: Decision.INVALID_REPORT).")
      .def_property_readonly(
          "dropped",
          [](const ReplannerHandle& h) {
            return dropped_of(h.replanner->dropped(), h.replanner->mission());
          },
          "Every task left out so far (DroppedTask).")
      .def_property_readonly("done", &done_of, "The names of the tasks done.")
      .def("__repr__", [](const ReplannerHandle& h) {
        return Repr("Replanner")
            .field("mission", h.mission->mission.name)
            .field("done", done_of(h).size())
            .field("dropped", h.replanner->dropped().size())
            .str();
      });
}

}  // namespace

void bind_planning(py::module_& m) {
  bind_plan_types(m);
  bind_plan_functions(m);
  bind_replanner(m);
}

}  // namespace sewerplan::python
