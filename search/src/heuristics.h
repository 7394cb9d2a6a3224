// SPDX-License-Identifier: MIT
// The factories of the heuristics of heuristic.h, one per file, called by make_heuristic().
//
// Private to search: heuristics.cc maps a HeuristicKind to one of these (and names the kinds);
// blind_heuristic.cc, combining_heuristic.cc (h_max and h_add) and ff_heuristic.cc each define
// one heuristic. A new heuristic is a file here plus one case in make_heuristic().
#pragma once

#include <memory>

#include "sewerplan/domain/compiled_task.h"
#include "sewerplan/search/heuristic.h"

#include "relaxed_task.h"

namespace sewerplan::search::detail {

// 0 at every state: A* with it is uniform-cost search.
std::unique_ptr<Heuristic> make_blind_heuristic();
// h_max (kMax) or h_add (kSum). `task` must outlive the heuristic.
std::unique_ptr<Heuristic> make_combining_heuristic(const domain::CompiledTask& task,
                                                    RelaxedExploration::Combine combine);
// FF's relaxed-plan heuristic, with helpful actions. `task` must outlive the heuristic.
std::unique_ptr<Heuristic> make_ff_heuristic(const domain::CompiledTask& task);

}  // namespace sewerplan::search::detail
