// SPDX-License-Identifier: MIT
// The heuristics' names and make_heuristic(); each heuristic lives in its own file (heuristics.h).
#include "heuristics.h"

#include "sewerplan/core/enum_names.h"
#include "sewerplan/search/heuristic.h"

namespace sewerplan::search {
namespace {

// sewerplan::detail in full: search::detail (relaxed_task.h) hides it here.
constexpr sewerplan::detail::EnumNames<HeuristicKind, 4> kHeuristicKinds{{
    {HeuristicKind::kFf, "ff"},
    {HeuristicKind::kAdd, "add"},
    {HeuristicKind::kMax, "max"},
    {HeuristicKind::kBlind, "blind"},
}};
static_assert(sewerplan::detail::distinct(kHeuristicKinds));

}  // namespace

std::string_view to_string(HeuristicKind kind) {
  return sewerplan::detail::name_of(kHeuristicKinds, kind);
}

std::optional<HeuristicKind> heuristic_from_string(std::string_view name) {
  return sewerplan::detail::value_of(kHeuristicKinds, name);
}

std::string heuristic_names() { return sewerplan::detail::names_joined(kHeuristicKinds); }

std::unique_ptr<Heuristic> make_heuristic(HeuristicKind kind, const domain::CompiledTask& task) {
  using detail::RelaxedExploration;
  switch (kind) {
    case HeuristicKind::kFf:
      return detail::make_ff_heuristic(task);
    case HeuristicKind::kAdd:
      return detail::make_combining_heuristic(task, RelaxedExploration::Combine::kSum);
    case HeuristicKind::kMax:
      return detail::make_combining_heuristic(task, RelaxedExploration::Combine::kMax);
    case HeuristicKind::kBlind:
      return detail::make_blind_heuristic();
  }
  return nullptr;
}

}  // namespace sewerplan::search
