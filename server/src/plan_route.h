// SPDX-License-Identifier: MIT
// A plan's route as the page draws it: {"steps": [the paper's text of each step], "pipes": [the
// pipes it drives or enters, in order]}, sent after each plan of a simulation (the event log does
// not carry it) and of a campaign run replayed.
#pragma once

#include "sewerplan/core/mission.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/plan.h"
#include "sewerplan/server/documents.h"

namespace sewerplan::server {

// Runtime: O(steps).
Json plan_route_json(const domain::Plan& plan, const SewerMap& map, const Mission& mission);

}  // namespace sewerplan::server
