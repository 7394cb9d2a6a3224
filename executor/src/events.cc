// SPDX-License-Identifier: MIT
// Event names and fields (events.h, event_fields.h).
#include "sewerplan/executor/events.h"

#include <array>
#include <utility>

#include "sewerplan/core/overloaded.h"

#include "enum_names.h"
#include "event_fields.h"

namespace sewerplan::executor {
namespace {

constexpr detail::EnumNames<MissionOutcome, 3> kOutcomes{{
    {MissionOutcome::kEnded, "ended"},
    {MissionOutcome::kBeacon, "beacon"},
    {MissionOutcome::kHalted, "halted"},
}};

constexpr detail::EnumNames<BeaconCause, 6> kBeaconCauses{{
    {BeaconCause::kNone, "none"},
    {BeaconCause::kNoExit, "no-exit"},
    {BeaconCause::kStuck, "stuck"},
    {BeaconCause::kMalfunction, "malfunction"},
    {BeaconCause::kLink, "link"},
    {BeaconCause::kLimit, "limit"},
}};

constexpr detail::EnumNames<HazardEvent::Observed, 2> kObserved{{
    {HazardEvent::Observed::kPassed, "passed"},
    {HazardEvent::Observed::kBlocked, "blocked"},
}};

static_assert(detail::distinct(kOutcomes) && detail::distinct(kBeaconCauses) &&
              detail::distinct(kObserved));

std::string text(std::string_view s) { return std::string(s); }

}  // namespace

std::string_view to_string(MissionOutcome outcome) { return detail::name_of(kOutcomes, outcome); }
std::optional<MissionOutcome> parse_mission_outcome(std::string_view name) {
  return detail::value_of(kOutcomes, name);
}
std::string_view to_string(BeaconCause cause) { return detail::name_of(kBeaconCauses, cause); }
std::optional<BeaconCause> parse_beacon_cause(std::string_view name) {
  return detail::value_of(kBeaconCauses, name);
}

std::string_view to_string(HazardEvent::Observed observed) {
  return detail::name_of(kObserved, observed);
}
std::optional<HazardEvent::Observed> parse_hazard_observed(std::string_view name) {
  return detail::value_of(kObserved, name);
}

std::string_view type_name(const Event& event) {
  return std::visit(
      Overloaded{
          [](const PlanEvent& e) -> std::string_view { return e.replan ? "replan" : "plan"; },
          [](const ActionEvent&) -> std::string_view { return "action"; },
          [](const JobEvent&) -> std::string_view { return "job"; },
          [](const ErrorEvent&) -> std::string_view { return "error"; },
          [](const RecoveryEvent&) -> std::string_view { return "recovery"; },
          [](const FailureEvent&) -> std::string_view { return "failure"; },
          [](const TaskDoneEvent&) -> std::string_view { return "task_done"; },
          [](const TaskDroppedEvent&) -> std::string_view { return "task_dropped"; },
          [](const ReserveEvent&) -> std::string_view { return "reserve"; },
          [](const ArrivalEvent&) -> std::string_view { return "arrival"; },
          [](const HazardEvent&) -> std::string_view { return "hazard"; },
          [](const BeaconEvent&) -> std::string_view { return "beacon"; },
          [](const MissionEndEvent&) -> std::string_view { return "mission_end"; }},
      event.what);
}

namespace detail {

Fields fields_of(const Event& event) {
  using I = std::int64_t;
  return std::visit(
      Overloaded{
          [](const PlanEvent& e) -> Fields {
            Fields f{{"reason", e.reason},
                     {"planning_ms", e.planning_ms},
                     {"decision", text(to_string(e.decision))},
                     {"goals", e.goals},
                     {"dropped", e.dropped},
                     {"end", e.end},
                     {"steps", static_cast<I>(e.steps)},
                     {"cost_s", e.cost_s}};
            if (e.rung != PlanResponse::Rung::kSearch)
              f.emplace_back("rung", text(to_string(e.rung)));
            if (e.strand_probability > 0)
              f.emplace_back("strand_probability", e.strand_probability);
            return f;
          },
          [](const ActionEvent& e) -> Fields {
            return {{"step", e.step},
                    {"kind", e.kind},
                    {"duration_s", e.duration_s},
                    {"parameters", e.parameters}};
          },
          [](const JobEvent& e) -> Fields {
            return {{"job", e.job}, {"progress_m", e.progress_m}, {"ok", e.ok}};
          },
          [](const ErrorEvent& e) -> Fields {
            return {
                {"kind", text(hal::to_string(e.kind))}, {"reason", e.reason}, {"where", e.where}};
          },
          [](const RecoveryEvent& e) -> Fields {
            return {{"phase", text(logged_name(e.phase))}, {"ok", e.ok}};
          },
          [](const FailureEvent& e) -> Fields {
            Fields f{{"kind", text(to_string(e.kind))}};
            if (const auto* in = std::get_if<FailureEvent::InPipe>(&e.where)) {
              f.emplace_back("pipe", in->pipe);
              f.emplace_back("offset_m", in->offset_m);
            } else if (const auto* p = std::get_if<FailureEvent::Passage>(&e.where)) {
              f.emplace_back("manhole", p->manhole);
              f.emplace_back("from_slot", static_cast<I>(p->from_slot));
              f.emplace_back("to_slot", static_cast<I>(p->to_slot));
            }
            f.emplace_back("detail", e.detail);
            return f;
          },
          [](const TaskDoneEvent& e) -> Fields {
            return {{"task", e.task}};
          },
          [](const TaskDroppedEvent& e) -> Fields {
            return {{"task", e.task}, {"reason", e.reason}};
          },
          [](const ReserveEvent& e) -> Fields {
            return {{"end", e.end},
                    {"energy_wh", e.energy_wh},
                    {"left_wh", e.left_wh},
                    {"reserve_wh", e.reserve_wh}};
          },
          [](const ArrivalEvent& e) -> Fields {
            return {
                {"expected", e.expected}, {"check", e.check},     {"probability", e.probability},
                {"believed", e.believed}, {"manhole", e.manhole}, {"observed", e.observed},
                {"reason", e.reason}};
          },
          [](const HazardEvent& e) -> Fields {
            return {{"pipe", e.pipe},
                    {"offset_m", e.offset_m},
                    {"reason", e.reason},
                    {"observed", text(to_string(e.observed))},
                    {"probability_before", e.probability_before},
                    {"probability", e.probability},
                    {"passes", static_cast<I>(e.passes)}};
          },
          [](const BeaconEvent& e) -> Fields {
            return {{"reason", e.reason}, {"state", text(hal::to_string(e.state))}};
          },
          [](const MissionEndEvent& e) -> Fields {
            Fields f{{"outcome", text(to_string(e.outcome))},
                     {"end", e.end},
                     {"tasks_done", e.tasks_done},
                     {"energy_wh", e.energy_wh},
                     {"replans", static_cast<I>(e.replans)},
                     {"decision", text(to_string(e.decision))},
                     {"beacon_cause", text(to_string(e.beacon_cause))}};
            // Absent when no beacon was asked for: the logs before it read the same.
            if (e.beacon != hal::BeaconState::kNone) {
              f.emplace_back("beacon", text(hal::to_string(e.beacon)));
            }
            return f;
          }},
      event.what);
}

}  // namespace detail
}  // namespace sewerplan::executor
