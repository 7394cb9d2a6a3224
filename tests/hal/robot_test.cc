// SPDX-License-Identifier: MIT
// The robot's error and beacon names (robot.h): each written once, read both ways.
#include "sewerplan/hal/robot.h"

#include <gtest/gtest.h>

#include "support/enum_round_trip.h"

namespace sewerplan::hal {
namespace {

using testing::expect_round_trip;

TEST(RobotNames, EveryValueRoundTripsThroughItsNameAndBack) {
  expect_round_trip(
      {RobotErrorKind::kBlockage, RobotErrorKind::kDanger, RobotErrorKind::kMalfunction},
      parse_robot_error_kind);
  expect_round_trip(
      {RobotErrorCause::kObstacle, RobotErrorCause::kBlindEnd, RobotErrorCause::kNoManholeSeen,
       RobotErrorCause::kNoMouth, RobotErrorCause::kOtherBlockage, RobotErrorCause::kDangerSpot,
       RobotErrorCause::kDangerousPassage, RobotErrorCause::kOtherDanger, RobotErrorCause::kFault,
       RobotErrorCause::kBatteryEmpty, RobotErrorCause::kInvalidJob, RobotErrorCause::kNotAtStart,
       RobotErrorCause::kEmergencyStop, RobotErrorCause::kLink, RobotErrorCause::kOtherMalfunction},
      parse_robot_error_cause);
  expect_round_trip({BeaconState::kNone, BeaconState::kConfirmed, BeaconState::kUnconfirmed,
                     BeaconState::kNotSent},
                    parse_beacon_state);
}

TEST(RobotNames, AnErrorTypedNoFurtherIsNamedAsItsKind) {
  for (RobotErrorKind kind :
       {RobotErrorKind::kBlockage, RobotErrorKind::kDanger, RobotErrorKind::kMalfunction}) {
    EXPECT_EQ(to_string(other_cause(kind)), to_string(kind));
  }
}

}  // namespace
}  // namespace sewerplan::hal
