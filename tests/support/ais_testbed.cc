// SPDX-License-Identifier: MIT
#include "support/ais_testbed.h"

#include <gtest/gtest.h>

#include "sewerplan/core/map_io.h"

#include "support/paths.h"

namespace sewerplan::testing {

AisTestbed load_ais_testbed() {
  AisTestbed ais;
  Diagnostics diagnostics;
  Result<SewerMap> map = read_map(dataset_path("ais-testbed/map.json"), diagnostics);
  EXPECT_TRUE(map.has_value()) << map.error();
  if (!map.has_value()) return ais;
  ais.map = std::move(map).value();
  Result<Mission> mission =
      read_mission(dataset_path("ais-testbed/missions/paper.json"), ais.map, diagnostics);
  EXPECT_TRUE(mission.has_value()) << mission.error();
  if (mission.has_value()) ais.mission = std::move(mission).value();
  return ais;
}

}  // namespace sewerplan::testing
