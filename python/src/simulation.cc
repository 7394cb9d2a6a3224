// SPDX-License-Identifier: MIT
// The Python module: simulated missions with faults (events as Python objects) and campaigns.
#include <functional>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sewerplan/campaign/campaign.h"
#include "sewerplan/campaign/summary.h"
#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/map_json.h"
#include "sewerplan/executor/event_json.h"
#include "sewerplan/executor/executor.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/hal/sim_robot.h"

#include "bindings.h"
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

namespace sewerplan::python {
namespace {

namespace ex = executor;

struct Faults {
  std::shared_ptr<const SewerMap> map;
  hal::FaultScenario scenario;
};

// A fault with the map's names, as Python sees it.
struct ObstacleView {
  std::string pipe;
  double offset_m = 0;
  std::string kind;
};
struct DangerSpotView {
  std::string pipe;
  double offset_m = 0;
};
struct PassageView {
  std::string manhole;
  unsigned from_slot = 0;
  unsigned to_slot = 0;
};
struct MalfunctionView {
  std::string kind;
  std::optional<std::uint32_t> at_job;
  std::optional<double> at_time_s;
};

struct Simulation {
  ex::MissionReport report;
  std::vector<ex::Event> events;
};

struct Campaign {
  std::vector<campaign::RunRecord> records;
  campaign::Summary summary;
};

// halt() for a simulation, settable from any Python thread: it halts the Executor of the
// simulate() call it was given to, or, before that call starts, makes it halt at once.
class Halter {
 public:
  void halt() {
    std::lock_guard lock(mutex_);
    requested_ = true;
    if (executor_ != nullptr) executor_->halt();
  }
  bool requested() const {
    std::lock_guard lock(mutex_);
    return requested_;
  }
  // While `executor` runs: halt() goes to it (and at once, if it was called already).
  void attach(ex::Executor* executor) {
    std::lock_guard lock(mutex_);
    executor_ = executor;
    if (executor_ != nullptr && requested_) executor_->halt();
  }

 private:
  mutable std::mutex mutex_;
  bool requested_ = false;
  ex::Executor* executor_ = nullptr;
};

hal::SimPose start_pose(const domain::RobotPosition& p) {
  if (const auto* in = std::get_if<domain::InManhole>(&p)) return hal::InManhole{in->manhole};
  if (const auto* at = std::get_if<domain::AtSlot>(&p)) return hal::AtSlot{at->manhole, at->slot};
  const auto& pipe = std::get<domain::InPipe>(p);
  return hal::InPipe{pipe.pipe, pipe.offset_m, hal::Heading::kTowardsEnd1};
}

Simulation simulate(const std::shared_ptr<const MissionHandle>& mission,
                    const std::optional<Faults>& faults, bool allow_push,
                    double planner_time_limit_s, const std::optional<py::function>& on_event,
                    const std::shared_ptr<Halter>& halter) {
  const SewerMap& map = *mission->map;
  if (faults && faults->map.get() != mission->map.get()) {
    raise_error({ErrorCode::kInvalidArgument, "the faults were read against another map"});
  }
  Simulation out;
  // The callback's exception, if it raised: the run is halted and it is raised here.
  std::optional<py::error_already_set> raised;
  {
    py::gil_scoped_release release;
    ex::ReplannerOptions replanner_options;
    replanner_options.planner.time_limit_s = planner_time_limit_s;
    ex::Replanner replanner(map, mission->mission, replanner_options);
    hal::SimRobot robot(map, mission->mission.profile, start_pose(replanner.progress().position),
                        faults ? faults->scenario : hal::FaultScenario{});
    ex::ExecutorOptions options;
    options.recovery.push_allowed = allow_push;
    ex::Executor executor(map, replanner, robot, options);
    executor.subscribe([&](const ex::Event& e) {
      out.events.push_back(e);
      if (!on_event || raised) return;
      // The GIL only for the callback: the simulation runs without it.
      py::gil_scoped_acquire gil;
      try {
        (*on_event)(e);
      } catch (py::error_already_set& error) {
        raised.emplace(std::move(error));
        executor.halt();
      }
    });
    if (halter) halter->attach(&executor);
    out.report = executor.run();
    if (halter) halter->attach(nullptr);
  }
  if (raised) throw std::move(*raised);
  return out;
}

Campaign run(const std::shared_ptr<const MissionHandle>& mission, std::size_t runs,
             std::uint64_t seed, const std::string& rates, std::size_t jobs, bool guard,
             double timeout_s, bool allow_push, const std::string& risk,
             const std::optional<std::filesystem::path>& risk_table, bool faults_from_condition,
             double planner_time_limit_s) {
  const SewerMap& map = *mission->map;
  // What the map's findings mean for planning, as `sewerplan campaign --risk` applies them.
  const std::optional<RiskMode> mode = risk_mode_from_string(risk);
  if (!mode) {
    raise_error({ErrorCode::kInvalidArgument,
                 "risk must be ignore, impassable, avoid or expected, not '" + risk + "'"});
  }
  Diagnostics diagnostics;
  const RiskTable table =
      risk_table ? value_or_raise(read_risk_table(*risk_table, diagnostics), &diagnostics)
                 : default_risk_table();
  Mission planned = mission->mission;
  // Obstacles drawn from the findings need their hazards: every policy plans with what the
  // findings close, the risk-aware one weighs the rest.
  close_findings(map, planned,
                 faults_from_condition && *mode != RiskMode::kAvoid ? RiskMode::kExpected : *mode,
                 table);
  if (faults_from_condition && planned.hazards.empty()) {
    raise_error({ErrorCode::kInvalidArgument,
                 "faults_from_condition: the map's findings hold no possible blockage"});
  }
  campaign::CampaignSpec spec;
  spec.map_name = map.name();
  spec.mission_name = mission->mission.name;
  std::ostringstream map_json;
  write_map_json(map, map_json);
  spec.map_fingerprint = campaign::fingerprint(map_json.str());
  std::ostringstream mission_json;
  write_mission_json(mission->mission, map, mission_json);
  spec.mission_fingerprint = campaign::fingerprint(mission_json.str());
  spec.seed = seed;
  spec.runs = runs;
  spec.rates = value_or_raise(campaign::parse_fault_rates(rates));
  spec.push_allowed = allow_push;
  spec.planner_time_limit_s = planner_time_limit_s;
  spec.risk = risk;
  spec.faults_from_condition = faults_from_condition;
  if (risk_table) {
    // A risk table changes what the findings mean: part of the mission's identity.
    std::ostringstream table_json;
    write_risk_table_json(table, table_json);
    spec.mission_fingerprint =
        campaign::fingerprint(spec.mission_fingerprint + "\nrisk-table:" + table_json.str());
  }
  campaign::CampaignOptions options;
  options.jobs = std::max<std::size_t>(1, jobs);
  options.guard = guard;
  options.timeout_s = timeout_s;
  Campaign out;
  {
    py::gil_scoped_release release;
    out.records = campaign::run_campaign(map, planned, spec, options);
    out.summary = campaign::summarize(spec, out.records);
  }
  return out;
}

template <class T>
std::string name_of(T value) {
  return std::string(ex::to_string(value));
}

void bind_events(py::module_& m) {
  py::class_<ex::PlanEvent>(m, "PlanEvent", "A plan or replan of a simulated mission.")
      .def_readonly("replan", &ex::PlanEvent::replan, "Whether it is a replan.")
      .def_readonly("reason", &ex::PlanEvent::reason,
                    "Why it was made ('start', 'blockage in P5 at 4.00 m'), or why there is none.")
      .def_readonly("planning_ms", &ex::PlanEvent::planning_ms, "Planning time (ms).")
      .def_readonly("decision", &ex::PlanEvent::decision, "The Replanner's Decision.")
      .def_readonly("goals", &ex::PlanEvent::goals, "The tasks the plan does.")
      .def_readonly("dropped", &ex::PlanEvent::dropped, "The tasks newly dropped.")
      .def_readonly("end", &ex::PlanEvent::end,
                    "Where the plan ends: 'exit M4', \"pipe P9 (final task 'end')\".")
      .def_readonly("steps", &ex::PlanEvent::steps, "How many steps.")
      .def_readonly("cost_s", &ex::PlanEvent::cost_s, "The plan's time (s).")
      .def("__repr__", [](const ex::PlanEvent& e) {
        return Repr("PlanEvent")
            .field("replan", e.replan)
            .field("reason", e.reason)
            .field("decision", std::string(ex::to_string(e.decision)))
            .field("steps", e.steps)
            .field("cost_s", e.cost_s)
            .str();
      });
  py::class_<ex::ActionEvent>(m, "ActionEvent", "An action the executor started.")
      .def_readonly("step", &ex::ActionEvent::step, "The plan step, in the paper's text.")
      .def_readonly("kind", &ex::ActionEvent::kind,
                    "The action's kind: 'drive_to_manhole', 'pass_manhole', ...")
      .def_readonly("duration_s", &ex::ActionEvent::duration_s, "Its expected time (s).")
      .def_readonly("parameters", &ex::ActionEvent::parameters, "The action with its parameters.")
      .def("__repr__", [](const ex::ActionEvent& e) {
        return Repr("ActionEvent")
            .word(e.step)
            .field("kind", e.kind)
            .field("duration_s", e.duration_s)
            .str();
      });
  py::class_<ex::JobEvent>(m, "JobEvent", "A job the robot ran, and how far it got.")
      .def_readonly("job", &ex::JobEvent::job, "The job: 'DriveForward(0.30 m/s, 2.83 m)'.")
      .def_readonly("progress_m", &ex::JobEvent::progress_m, "How far it got (m).")
      .def_readonly("ok", &ex::JobEvent::ok, "Whether it ended without an error.")
      .def("__repr__", [](const ex::JobEvent& e) {
        return Repr("JobEvent")
            .word(e.job)
            .field("progress_m", e.progress_m)
            .field("ok", e.ok)
            .str();
      });
  py::class_<ex::ErrorEvent>(m, "ErrorEvent", "The robot's error for the job before it.")
      .def_property_readonly(
          "kind", [](const ex::ErrorEvent& e) { return std::string(hal::to_string(e.kind)); },
          "The robot's error: 'blockage', 'danger' or 'malfunction'.")
      .def_readonly("reason", &ex::ErrorEvent::reason, "The robot's words.")
      .def_readonly("where", &ex::ErrorEvent::where,
                    "Where the executor's dead reckoning puts the robot.")
      .def("__repr__", [](const ex::ErrorEvent& e) {
        return Repr("ErrorEvent")
            .field("kind", std::string(hal::to_string(e.kind)))
            .field("reason", e.reason)
            .field("where", e.where)
            .str();
      });
  py::class_<ex::RecoveryEvent>(m, "RecoveryEvent",
                                "A recovery phase tried, and whether it cleared the error.")
      .def_property_readonly(
          "phase", [](const ex::RecoveryEvent& e) { return std::string(ex::logged_name(e.phase)); },
          "The recovery phase tried.")
      .def_readonly("ok", &ex::RecoveryEvent::ok, "Whether the phase cleared the error.")
      .def("__repr__", [](const ex::RecoveryEvent& e) {
        return Repr("RecoveryEvent")
            .field("phase", std::string(ex::logged_name(e.phase)))
            .field("ok", e.ok)
            .str();
      });
  py::class_<ex::FailureEvent>(m, "FailureEvent",
                               "A failure recovery could not clear, reported to the Replanner.")
      .def_readonly("kind", &ex::FailureEvent::kind, "The FailureKind.")
      .def_property_readonly(
          "pipe",
          [](const ex::FailureEvent& e) -> std::optional<std::string> {
            const auto* in = std::get_if<ex::FailureEvent::InPipe>(&e.where);
            if (in == nullptr) return std::nullopt;
            return in->pipe;
          },
          "The pipe of a blockage or danger spot, else None.")
      .def_property_readonly(
          "offset_m",
          [](const ex::FailureEvent& e) -> std::optional<double> {
            const auto* in = std::get_if<ex::FailureEvent::InPipe>(&e.where);
            if (in == nullptr) return std::nullopt;
            return in->offset_m;
          },
          "Its distance from the pipe's first end (m), else None.")
      .def_property_readonly(
          "manhole",
          [](const ex::FailureEvent& e) -> std::optional<std::string> {
            const auto* p = std::get_if<ex::FailureEvent::Passage>(&e.where);
            if (p == nullptr) return std::nullopt;
            return p->manhole;
          },
          "The manhole of a dangerous passage, else None.")
      .def_readonly("detail", &ex::FailureEvent::detail, "What the robot reported.")
      .def("__repr__", [](const ex::FailureEvent& e) {
        return Repr("FailureEvent")
            .field("kind", std::string(ex::to_string(e.kind)))
            .field("detail", e.detail)
            .str();
      });
  py::class_<ex::TaskDoneEvent>(m, "TaskDoneEvent", "A task done.")
      .def_readonly("task", &ex::TaskDoneEvent::task, "The task's name.")
      .def("__repr__",
           [](const ex::TaskDoneEvent& e) { return Repr("TaskDoneEvent").word(e.task).str(); });
  py::class_<ex::TaskDroppedEvent>(m, "TaskDroppedEvent", "A task dropped, and why.")
      .def_readonly("task", &ex::TaskDroppedEvent::task, "The task's name.")
      .def_readonly("reason", &ex::TaskDroppedEvent::reason, "Why it was dropped.")
      .def("__repr__", [](const ex::TaskDroppedEvent& e) {
        return Repr("TaskDroppedEvent").word(e.task).field("reason", e.reason).str();
      });
  py::class_<ex::ReserveEvent>(m, "ReserveEvent", "The robot sent out on its battery reserve.")
      .def_readonly("end", &ex::ReserveEvent::end, "The exit it heads for: 'exit M4'.")
      .def_readonly("energy_wh", &ex::ReserveEvent::energy_wh, "What the way out needs (Wh).")
      .def_readonly("left_wh", &ex::ReserveEvent::left_wh,
                    "The charge the robot reports left (Wh).")
      .def_readonly("reserve_wh", &ex::ReserveEvent::reserve_wh, "The operator's reserve (Wh).")
      .def("__repr__", [](const ex::ReserveEvent& e) {
        return Repr("ReserveEvent")
            .field("end", e.end)
            .field("left_wh", e.left_wh)
            .field("reserve_wh", e.reserve_wh)
            .str();
      });
  py::class_<ex::ArrivalEvent>(m, "ArrivalEvent",
                               "A check of where the robot arrived against the map.")
      .def_readonly("expected", &ex::ArrivalEvent::expected,
                    "Where the plan has the robot: 'M6 slot 2'; empty: in a pipe.")
      .def_readonly("check", &ex::ArrivalEvent::check,
                    "'matches', 'wrong-manhole', 'unmapped-junction', 'missed-manhole', "
                    "'false-detection' or 'signature-differs'.")
      .def_readonly("probability", &ex::ArrivalEvent::probability,
                    "That the robot is where the plan has it (0 to 1).")
      .def_readonly("believed", &ex::ArrivalEvent::believed,
                    "The most likely place: 'at M7 slot 1 (P9)'; empty: lost.")
      .def_readonly("manhole", &ex::ArrivalEvent::manhole,
                    "The manhole of that place; empty: none on the map.")
      .def_readonly("observed", &ex::ArrivalEvent::observed,
                    "The signature seen: '4 slots at 0, 92, 181, 268°'.")
      .def_readonly("reason", &ex::ArrivalEvent::reason,
                    "Why it does not match; empty when it does.")
      .def("__repr__", [](const ex::ArrivalEvent& e) {
        return Repr("ArrivalEvent")
            .field("expected", e.expected)
            .field("observed", e.observed)
            .field("reason", e.reason)
            .str();
      });
  py::class_<ex::HazardEvent>(m, "HazardEvent",
                              "A hazard's blockage probability learnt from what the robot met.")
      .def_readonly("pipe", &ex::HazardEvent::pipe, "The hazard's pipe.")
      .def_readonly("offset_m", &ex::HazardEvent::offset_m, "Its offset in the pipe (m).")
      .def_readonly("reason", &ex::HazardEvent::reason, "The finding: 'BBA roots'.")
      .def_property_readonly(
          "observed", [](const ex::HazardEvent& e) { return name_of(e.observed); },
          "'passed' (driven past safely) or 'blocked' (met as a blockage).")
      .def_readonly("probability_before", &ex::HazardEvent::probability_before,
                    "The probability before (0 to 1).")
      .def_readonly("probability", &ex::HazardEvent::probability, "The probability after (0 to 1).")
      .def_readonly("passes", &ex::HazardEvent::passes, "Safe passes observed so far.")
      .def("__repr__", [](const ex::HazardEvent& e) {
        return Repr("HazardEvent")
            .word(e.pipe)
            .field("observed", name_of(e.observed))
            .field("probability", e.probability)
            .str();
      });
  py::class_<ex::BeaconEvent>(m, "BeaconEvent",
                              "The beacon switched on: the robot calls for recovery.")
      .def_readonly("reason", &ex::BeaconEvent::reason, "Why the robot calls for recovery.")
      .def("__repr__", [](const ex::BeaconEvent& e) {
        return Repr("BeaconEvent").field("reason", e.reason).str();
      });
  py::class_<ex::MissionEndEvent>(m, "MissionEndEvent", "The end of the mission: how it went.")
      .def_property_readonly(
          "outcome", [](const ex::MissionEndEvent& e) { return name_of(e.outcome); },
          "'ended', 'beacon' or 'halted'.")
      .def_readonly("end", &ex::MissionEndEvent::end,
                    "'exit M4', why the beacon is on, or where the robot was halted.")
      .def_readonly("tasks_done", &ex::MissionEndEvent::tasks_done, "The tasks done, in order.")
      .def_readonly("energy_wh", &ex::MissionEndEvent::energy_wh, "Energy used (Wh).")
      .def_readonly("replans", &ex::MissionEndEvent::replans, "How many replans.")
      .def_readonly("decision", &ex::MissionEndEvent::decision, "The Replanner's last Decision.")
      .def_property_readonly(
          "beacon_cause", [](const ex::MissionEndEvent& e) { return name_of(e.beacon_cause); },
          "Why the beacon is on: 'none', 'no-exit', 'stuck', 'malfunction', 'link', 'limit'.")
      .def("__repr__", [](const ex::MissionEndEvent& e) {
        return Repr("MissionEndEvent")
            .field("outcome", name_of(e.outcome))
            .field("end", e.end)
            .field("energy_wh", e.energy_wh)
            .field("replans", e.replans)
            .str();
      });
  py::class_<ex::Event>(m, "Event",
                        "One thing that happened in a simulated mission: t_s, type, and `what`, "
                        "the event's own object (PlanEvent, ActionEvent, ...).")
      .def_readonly("t_s", &ex::Event::t_s, "Mission time (s).")
      .def_property_readonly(
          "type", [](const ex::Event& e) { return std::string(ex::type_name(e)); },
          "'plan', 'replan', 'action', 'job', 'error', 'recovery', 'failure', 'task_done', "
          "'task_dropped', 'beacon', 'mission_end', ...")
      .def_readonly("what", &ex::Event::what, "The event's own object (PlanEvent, ...).")
      .def("to_json", &ex::to_json_line, "The event's line in the JSON-lines log.")
      .def("__repr__", [](const ex::Event& e) { return "<Event " + ex::to_json_line(e) + ">"; });
}

void bind_simulate(py::module_& m) {
  py::class_<ObstacleView>(m, "Obstacle", "Something in a pipe that stops the robot.")
      .def_readonly("pipe", &ObstacleView::pipe, "The pipe's name.")
      .def_readonly("offset_m", &ObstacleView::offset_m, "From the pipe's first end (m).")
      .def_readonly("kind", &ObstacleView::kind, "'permanent' or 'transient'")
      .def("__repr__", [](const ObstacleView& o) {
        return Repr("Obstacle")
            .word(o.kind)
            .field("pipe", o.pipe)
            .field("offset_m", o.offset_m)
            .str();
      });
  py::class_<DangerSpotView>(m, "DangerSpot", "A place in a pipe the robot must not drive onto.")
      .def_readonly("pipe", &DangerSpotView::pipe, "The pipe's name.")
      .def_readonly("offset_m", &DangerSpotView::offset_m, "From the pipe's first end (m).")
      .def("__repr__", [](const DangerSpotView& d) {
        return Repr("DangerSpot").field("pipe", d.pipe).field("offset_m", d.offset_m).str();
      });
  py::class_<PassageView>(m, "DangerousPassage",
                          "A passage of a manhole between two slots the robot must not take.")
      .def_readonly("manhole", &PassageView::manhole, "The manhole's name.")
      .def_readonly("from_slot", &PassageView::from_slot, "The slot it comes from (from 0).")
      .def_readonly("to_slot", &PassageView::to_slot, "The slot it goes to (from 0).")
      .def("__repr__", [](const PassageView& p) {
        return Repr("DangerousPassage")
            .field("manhole", p.manhole)
            .field("from_slot", p.from_slot)
            .field("to_slot", p.to_slot)
            .str();
      });
  py::class_<MalfunctionView>(m, "Malfunction", "A robot malfunction, at a job or a time.")
      .def_readonly("kind", &MalfunctionView::kind, "'transient' or 'permanent'")
      .def_readonly("at_job", &MalfunctionView::at_job, "the job's index from 0, or None")
      .def_readonly("at_time_s", &MalfunctionView::at_time_s, "the mission time (s), or None")
      .def("__repr__", [](const MalfunctionView& v) {
        return Repr("Malfunction")
            .word(v.kind)
            .field("at_job", v.at_job)
            .field("at_time_s", v.at_time_s)
            .str();
      });
  py::class_<Faults>(m, "FaultScenario",
                     "The trouble hidden in a simulated sewer: lists of Obstacle, DangerSpot, "
                     "DangerousPassage and Malfunction objects.")
      .def_property_readonly(
          "obstacles",
          [](const Faults& f) {
            std::vector<ObstacleView> out;
            for (const hal::Obstacle& o : f.scenario.obstacles) {
              out.push_back(
                  {f.map->pipe(o.pipe).name, o.offset_m, std::string(hal::to_string(o.kind))});
            }
            return out;
          },
          "Every Obstacle.")
      .def_property_readonly(
          "danger_spots",
          [](const Faults& f) {
            std::vector<DangerSpotView> out;
            for (const hal::DangerSpot& d : f.scenario.danger_spots) {
              out.push_back({f.map->pipe(d.pipe).name, d.offset_m});
            }
            return out;
          },
          "Every DangerSpot.")
      .def_property_readonly(
          "dangerous_passages",
          [](const Faults& f) {
            std::vector<PassageView> out;
            for (const hal::DangerousPassage& p : f.scenario.dangerous_passages) {
              out.push_back(
                  {f.map->manhole(p.manhole).name, p.from_slot.value(), p.to_slot.value()});
            }
            return out;
          },
          "Every DangerousPassage.")
      .def_property_readonly(
          "malfunctions",
          [](const Faults& f) {
            std::vector<MalfunctionView> out;
            for (const hal::Malfunction& mf : f.scenario.malfunctions) {
              MalfunctionView v{.kind = std::string(hal::to_string(mf.kind))};
              if (const auto* j = std::get_if<hal::AtJob>(&mf.when)) {
                v.at_job = j->index;
              } else {
                v.at_time_s = std::get<hal::AtTime>(mf.when).time_s;
              }
              out.push_back(std::move(v));
            }
            return out;
          },
          "Every Malfunction.")
      .def(
          "to_json", [](const Faults& f) { return hal::faults_json(f.scenario, *f.map); },
          "The scenario in the fault file's JSON format (docs/simulation.md).")
      .def("__repr__", [](const Faults& f) {
        return Repr("FaultScenario")
            .field("map", f.map->name())
            .field("obstacles", f.scenario.obstacles.size())
            .field("danger_spots", f.scenario.danger_spots.size())
            .field("dangerous_passages", f.scenario.dangerous_passages.size())
            .field("malfunctions", f.scenario.malfunctions.size())
            .str();
      });
  m.def(
      "read_faults",
      [](std::shared_ptr<const SewerMap> map, const std::filesystem::path& path) {
        Diagnostics diagnostics;
        hal::FaultScenario s =
            value_or_raise(hal::read_faults(path, *map, diagnostics), &diagnostics);
        return Faults{std::move(map), std::move(s)};
      },
      py::arg("map"), py::arg("path"), "Reads a fault scenario (docs/simulation.md).");
  m.def(
      "random_faults",
      [](const std::shared_ptr<const MissionHandle>& mission, std::uint64_t seed,
         double obstacles_per_km) {
        // As `sewerplan simulate --random-faults SEED,RATE` draws them.
        hal::RandomFaultOptions r = hal::random_fault_options(mission->mission.profile);
        r.seed = seed;
        r.obstacle_rate_per_km = obstacles_per_km;
        r.danger_rate_per_km = obstacles_per_km / 4;
        r.malfunction_rate_per_hour = 0.5;
        return Faults{mission->map, value_or_raise(hal::random_faults(*mission->map, r))};
      },
      py::arg("mission"), py::arg("seed"), py::arg("obstacles_per_km") = 20.0,
      "Random faults where the mission's robot fits, as simulate --random-faults draws them; "
      "obstacles_per_km: obstacles per km of pipe (danger spots a quarter of that).");
  py::class_<ex::MissionReport>(m, "MissionReport", "How a simulated mission went.")
      .def_property_readonly(
          "outcome", [](const ex::MissionReport& r) { return name_of(r.outcome); },
          "'ended', 'beacon' or 'halted'.")
      .def_readonly("decision", &ex::MissionReport::decision, "The Replanner's last Decision.")
      .def_property_readonly(
          "beacon_cause", [](const ex::MissionReport& r) { return name_of(r.beacon_cause); },
          "Why the beacon is on: 'none', 'no-exit', 'stuck', 'malfunction', 'link', 'limit'.")
      .def_readonly("end", &ex::MissionReport::end, "'exit M4', why the beacon is on, ...")
      .def_readonly("tasks_done", &ex::MissionReport::tasks_done, "In the order done.")
      .def_readonly("dropped", &ex::MissionReport::dropped, "(task, reason) of each task not done.")
      .def_readonly("time_s", &ex::MissionReport::time_s, "Mission time (s).")
      .def_readonly("energy_wh", &ex::MissionReport::energy_wh, "Energy used (Wh).")
      .def_readonly("replans", &ex::MissionReport::replans, "How many replans.")
      .def_readonly("planning_times_s", &ex::MissionReport::planning_times_s,
                    "Each plan's planning time (s).")
      .def_readonly("jobs", &ex::MissionReport::jobs, "Robot jobs run.")
      .def_readonly("recoveries", &ex::MissionReport::recoveries,
                    "Errors cleared by recovery, without a replan.")
      .def_readonly("battery_reserve_kept", &ex::MissionReport::battery_reserve_kept,
                    "Whether the battery left is at least the reserve.")
      .def_readonly("log_errors", &ex::MissionReport::log_errors, "Logs that lost events.")
      .def_readonly("exit_on_reserve", &ex::MissionReport::exit_on_reserve,
                    "Whether the robot went out on its battery reserve.")
      .def("__repr__", [](const ex::MissionReport& r) {
        return Repr("MissionReport")
            .field("outcome", name_of(r.outcome))
            .field("end", r.end)
            .field("tasks_done", r.tasks_done.size())
            .field("dropped", r.dropped.size())
            .field("time_s", r.time_s)
            .field("energy_wh", r.energy_wh)
            .field("replans", r.replans)
            .str();
      });
  py::class_<Simulation>(m, "Simulation", "simulate()'s answer: the report and every event.")
      .def_readonly("report", &Simulation::report, "The MissionReport.")
      .def_readonly("events", &Simulation::events, "Every Event, in order.")
      .def("__repr__", [](const Simulation& sim) {
        return Repr("Simulation")
            .field("outcome", name_of(sim.report.outcome))
            .field("events", sim.events.size())
            .field("time_s", sim.report.time_s)
            .str();
      });
  py::class_<Halter, std::shared_ptr<Halter>>(
      m, "Halter", "halt() for simulate(), from any thread: the running mission stops.")
      .def("halt", &Halter::halt,
           "Stops the simulate() call given this Halter (at once if it has not started): the "
           "robot's emergency stop, then a mission_end event with outcome 'halted'.")
      .def(py::init<>(), "A Halter not yet halted.")
      .def_property_readonly("requested", &Halter::requested, "Whether halt() was called.")
      .def("__repr__",
           [](const Halter& h) { return Repr("Halter").field("requested", h.requested()).str(); });
  m.def("simulate", &simulate, py::arg("mission"), py::arg("faults") = py::none(),
        py::arg("allow_push") = false, py::arg("planner_time_limit_s") = 0.0,
        py::arg("on_event") = py::none(), py::arg("halt") = py::none(),
        "Runs the mission on the simulated robot with the faults hidden in it, with recovery "
        "and replanning, as `sewerplan simulate` does. The GIL is released meanwhile and taken "
        "only to call on_event(event) as each event happens (an exception it raises halts the "
        "run and is raised here); a Halter given as halt stops the run from another thread.");
}

void bind_campaign(py::module_& m) {
  py::class_<ex::HazardBelief>(
      m, "HazardBelief",
      "What a run observed of one hazard of the condition data (issue 34; the observations "
      "`sewerplan fit-risk` fits the risk table from).")
      .def_property_readonly(
          "pipe", [](const ex::HazardBelief& h) { return h.pipe.value(); },
          "The hazard's pipe, by its index in the map's pipes (as runs.jsonl has it).")
      .def_readonly("offset_m", &ex::HazardBelief::offset_m, "Its offset in the pipe (m).")
      .def_readonly("reason", &ex::HazardBelief::reason, "The finding: 'BBA roots'.")
      .def_readonly("passes", &ex::HazardBelief::passes, "Safe passes observed.")
      .def_readonly("blocked", &ex::HazardBelief::blocked, "Whether it stopped the robot.")
      .def_readonly("probability", &ex::HazardBelief::probability,
                    "Its blockage probability at the end of the run (0 to 1; 1 if blocked).")
      .def("__repr__", [](const ex::HazardBelief& h) {
        return Repr("HazardBelief")
            .field("pipe", h.pipe.value())
            .field("offset_m", h.offset_m)
            .field("reason", h.reason)
            .field("passes", h.passes)
            .field("blocked", h.blocked)
            .field("probability", h.probability)
            .str();
      });
  py::class_<campaign::Execution>(m, "Execution", "One policy's run of a campaign run.")
      .def_readonly("tasks", &campaign::Execution::tasks, "Tasks done.")
      .def_property_readonly(
          "outcome",
          [](const campaign::Execution& e) { return std::string(campaign::to_string(e.outcome)); },
          "How the run ended: 'exit', 'end_point', 'beacon' or 'stranded'.")
      .def_readonly("end", &campaign::Execution::end,
                    "The executor's words: 'exit M4', or why the beacon is on.")
      .def_readonly("reserve_kept", &campaign::Execution::reserve_kept,
                    "Whether the battery reserve was kept.")
      .def_readonly("replans", &campaign::Execution::replans, "How many replans.")
      .def_readonly("time_s", &campaign::Execution::time_s, "Mission time (s).")
      .def_readonly("energy_wh", &campaign::Execution::energy_wh, "Energy used (Wh).")
      .def_readonly("hazards", &campaign::Execution::hazards,
                    "Each HazardBelief: the hazards the robot drove past or was stopped by, in "
                    "the order first met (empty without condition data).")
      .def("__repr__", [](const campaign::Execution& e) {
        return Repr("Execution")
            .field("outcome", std::string(campaign::to_string(e.outcome)))
            .field("tasks", e.tasks)
            .field("end", e.end)
            .field("time_s", e.time_s)
            .str();
      });
  py::class_<campaign::RunRecord>(m, "RunRecord", "One run of a campaign.")
      .def_readonly("index", &campaign::RunRecord::index, "The run's index (from 0).")
      .def_readonly("seed", &campaign::RunRecord::seed, "The run's seed (its faults).")
      .def_property_readonly(
          "status",
          [](const campaign::RunRecord& r) { return std::string(campaign::to_string(r.status)); },
          "'ok', 'crash' or 'hang' (no result).")
      .def_readonly("detail", &campaign::RunRecord::detail,
                    "What went wrong, for a run that did not complete.")
      .def_property_readonly(
          "tasks",
          [](const campaign::RunRecord& r) -> std::optional<std::size_t> {
            if (!r.result) return std::nullopt;
            return r.result->tasks;
          },
          "Tasks ours did, or None without a result.")
      .def_property_readonly(
          "oracle_tasks",
          [](const campaign::RunRecord& r) -> std::optional<std::size_t> {
            if (!r.result) return std::nullopt;
            return r.result->oracle_tasks;
          },
          "Tasks the oracle does, or None without a result.")
      .def_property_readonly(
          "ours",
          [](const campaign::RunRecord& r) -> std::optional<campaign::Execution> {
            if (!r.result) return std::nullopt;
            return r.result->ours;
          },
          "Our policy's Execution, or None without a result.")
      .def_property_readonly(
          "risk_aware",
          [](const campaign::RunRecord& r) -> std::optional<campaign::Execution> {
            if (!r.result || !r.result->risk_aware) return std::nullopt;
            return *r.result->risk_aware;
          },
          "With risk='expected': the risk-aware policy's run, else None.")
      .def_property_readonly(
          "baseline",
          [](const campaign::RunRecord& r) -> std::optional<campaign::Execution> {
            if (!r.result) return std::nullopt;
            return r.result->baseline;
          },
          "The paper-era baseline's Execution, or None without a result.")
      .def("to_json", &campaign::run_json_line, "The run's line in runs.jsonl.")
      .def("__repr__", [](const campaign::RunRecord& r) {
        Repr repr("RunRecord");
        repr.field("index", r.index)
            .field("seed", r.seed)
            .field("status", std::string(campaign::to_string(r.status)));
        if (r.result)
          repr.field("tasks", r.result->tasks).field("oracle_tasks", r.result->oracle_tasks);
        return repr.str();
      });
  py::class_<campaign::Summary>(m, "CampaignSummary",
                                "A campaign's summary (summary.json, docs/campaign.md).")
      .def_readonly("runs", &campaign::Summary::runs, "Runs summarized.")
      .def_readonly("completed", &campaign::Summary::completed, "Runs with a result.")
      .def_readonly("could_reach_exit", &campaign::Summary::could_reach_exit,
                    "Runs in which ours could reach an exit.")
      .def_readonly("oracle_tasks_mean", &campaign::Summary::oracle_tasks_mean,
                    "Tasks the oracle (knowing the faults) does, on average.")
      .def_property_readonly(
          "ours_tasks_mean", [](const campaign::Summary& s) { return s.ours.tasks_mean; },
          "Tasks ours did, on average.")
      .def_property_readonly(
          "baseline_tasks_mean", [](const campaign::Summary& s) { return s.baseline.tasks_mean; },
          "Tasks the baseline did, on average.")
      .def_readonly("better_than_baseline", &campaign::Summary::better_than_baseline,
                    "Runs in which ours did more tasks than the baseline.")
      .def_readonly("equal_to_baseline", &campaign::Summary::equal_to_baseline,
                    "Runs in which ours did as many tasks.")
      .def_readonly("worse_than_baseline", &campaign::Summary::worse_than_baseline,
                    "Runs in which ours did fewer tasks.")
      .def_property_readonly("clean", &campaign::Summary::clean,
                             "No crash, hang, missed exit, stranded robot or reserve violation.")
      .def(
          "to_json",
          [](const campaign::Summary& s) {
            std::ostringstream out;
            campaign::write_summary_json(s, out);
            return out.str();
          },
          "summary.json.")
      .def("__repr__", [](const campaign::Summary& s) {
        return Repr("CampaignSummary")
            .field("runs", s.runs)
            .field("completed", s.completed)
            .field("ours_tasks_mean", s.ours.tasks_mean)
            .field("baseline_tasks_mean", s.baseline.tasks_mean)
            .field("clean", s.clean())
            .str();
      });
  py::class_<Campaign>(m, "Campaign", "run_campaign()'s answer.")
      .def_readonly("records", &Campaign::records, "Each RunRecord, by run index.")
      .def_readonly("summary", &Campaign::summary, "The CampaignSummary.")
      .def("__repr__", [](const Campaign& c) {
        return Repr("Campaign")
            .field("runs", c.records.size())
            .field("clean", c.summary.clean())
            .str();
      });
  m.def("run_campaign", &run, py::arg("mission"), py::arg("runs"), py::arg("seed") = 1,
        py::arg("rates") = "", py::arg("jobs") = 1, py::arg("guard") = true,
        py::arg("timeout_s") = 60.0, py::arg("allow_push") = false, py::arg("risk") = "impassable",
        py::arg("risk_table") = py::none(), py::arg("faults_from_condition") = false,
        py::arg("planner_time_limit_s") = 0.0,
        "Seeded simulated runs with random faults, each against the oracle and the paper-era "
        "baseline (sewerplan campaign; rates as --fault-rates writes them). risk, risk_table and "
        "faults_from_condition are the campaign's --risk, --risk-table and "
        "--faults-from-condition, applied to the map's findings (read_condition). The GIL is "
        "released meanwhile.");
}

}  // namespace

void bind_simulation(py::module_& m) {
  bind_events(m);
  bind_simulate(m);
  bind_campaign(m);
}

}  // namespace sewerplan::python
