// SPDX-License-Identifier: MIT
// Event names and fields (events.h, event_fields.h).
#include "sewerplan/executor/events.h"

#include <array>
#include <utility>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/overloaded.h"

#include "event_fields.h"

namespace sewerplan::executor {
namespace {

// sewerplan::detail in full: executor::detail (event_fields.h) hides it here.
constexpr sewerplan::detail::EnumNames<MissionOutcome, 3> kOutcomes{{
    {MissionOutcome::kEnded, "ended"},
    {MissionOutcome::kBeacon, "beacon"},
    {MissionOutcome::kHalted, "halted"},
}};

constexpr sewerplan::detail::EnumNames<BeaconCause, 6> kBeaconCauses{{
    {BeaconCause::kNone, "none"},
    {BeaconCause::kNoExit, "no-exit"},
    {BeaconCause::kStuck, "stuck"},
    {BeaconCause::kMalfunction, "malfunction"},
    {BeaconCause::kLink, "link"},
    {BeaconCause::kLimit, "limit"},
}};

constexpr sewerplan::detail::EnumNames<HazardEvent::Observed, 2> kObserved{{
    {HazardEvent::Observed::kPassed, "passed"},
    {HazardEvent::Observed::kBlocked, "blocked"},
}};

// The event log's `type` names (event_fields.h).
constexpr sewerplan::detail::EnumNames<detail::EventType, 14> kEventTypes{{
    {detail::EventType::kPlan, "plan"},
    {detail::EventType::kReplan, "replan"},
    {detail::EventType::kAction, "action"},
    {detail::EventType::kJob, "job"},
    {detail::EventType::kError, "error"},
    {detail::EventType::kRecovery, "recovery"},
    {detail::EventType::kFailure, "failure"},
    {detail::EventType::kTaskDone, "task_done"},
    {detail::EventType::kTaskDropped, "task_dropped"},
    {detail::EventType::kReserve, "reserve"},
    {detail::EventType::kArrival, "arrival"},
    {detail::EventType::kHazard, "hazard"},
    {detail::EventType::kBeacon, "beacon"},
    {detail::EventType::kMissionEnd, "mission_end"},
}};

static_assert(sewerplan::detail::distinct(kEventTypes) && sewerplan::detail::distinct(kOutcomes) &&
              sewerplan::detail::distinct(kBeaconCauses) && sewerplan::detail::distinct(kObserved));

std::string text(std::string_view s) { return std::string(s); }

}  // namespace

std::string_view to_string(MissionOutcome outcome) {
  return sewerplan::detail::name_of(kOutcomes, outcome);
}
std::optional<MissionOutcome> parse_mission_outcome(std::string_view name) {
  return sewerplan::detail::value_of(kOutcomes, name);
}
std::string_view to_string(BeaconCause cause) {
  return sewerplan::detail::name_of(kBeaconCauses, cause);
}
std::optional<BeaconCause> parse_beacon_cause(std::string_view name) {
  return sewerplan::detail::value_of(kBeaconCauses, name);
}

std::string_view to_string(HazardEvent::Observed observed) {
  return sewerplan::detail::name_of(kObserved, observed);
}
std::optional<HazardEvent::Observed> parse_hazard_observed(std::string_view name) {
  return sewerplan::detail::value_of(kObserved, name);
}

std::string_view type_name(const Event& event) { return to_string(detail::type_of(event)); }

namespace detail {

EventType type_of(const Event& event) {
  return std::visit(Overloaded{[](const PlanEvent& e) {
                                 return e.replan ? EventType::kReplan : EventType::kPlan;
                               },
                               [](const ActionEvent&) { return EventType::kAction; },
                               [](const JobEvent&) { return EventType::kJob; },
                               [](const ErrorEvent&) { return EventType::kError; },
                               [](const RecoveryEvent&) { return EventType::kRecovery; },
                               [](const FailureEvent&) { return EventType::kFailure; },
                               [](const TaskDoneEvent&) { return EventType::kTaskDone; },
                               [](const TaskDroppedEvent&) { return EventType::kTaskDropped; },
                               [](const ReserveEvent&) { return EventType::kReserve; },
                               [](const ArrivalEvent&) { return EventType::kArrival; },
                               [](const HazardEvent&) { return EventType::kHazard; },
                               [](const BeaconEvent&) { return EventType::kBeacon; },
                               [](const MissionEndEvent&) { return EventType::kMissionEnd; }},
                    event.what);
}

std::string_view to_string(EventType type) { return sewerplan::detail::name_of(kEventTypes, type); }

std::optional<EventType> parse_event_type(std::string_view name) {
  return sewerplan::detail::value_of(kEventTypes, name);
}

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
