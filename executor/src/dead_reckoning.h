// SPDX-License-Identifier: MIT
// DeadReckoning: where the robot is in planning terms, from the jobs it ran and how far each got.
//
// Private to executor. The planner needs the robot's position (in a pipe at an offset, at a
// manhole's pipe mouth, in a manhole) to replan from; the executor knows it only from the jobs
// it sent and their reports. A drive moves along the pipe, forward towards the end the robot's
// front points to; reaching an end with a manhole puts it at that mouth (a drive of 0 m done
// right at that end, too); a turn through a manhole or leaving the start manhole puts it into the
// new pipe, facing away from the manhole.
#pragma once

#include <cstdint>
#include <string>

#include "sewerplan/core/job.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/domain/robot_state.h"
#include "sewerplan/hal/robot.h"

namespace sewerplan::executor::detail {

class DeadReckoning {
 public:
  DeadReckoning(const SewerMap& map, domain::RobotPosition start, std::uint8_t heading_end)
      : map_(map), position_(start), heading_end_(heading_end) {}

  void advance(const Job& job, const hal::JobReport& report);
  // After a plan step whose position agrees with this one, the validator's is exact; the heading
  // is kept.
  void set_position(const domain::RobotPosition& p) { position_ = p; }
  // Where the robot was found to be (manhole verification): its place and, in a pipe, heading.
  void set_pose(const domain::RobotPosition& p, std::uint8_t heading_end) {
    position_ = p;
    heading_end_ = heading_end;
  }

  const domain::RobotPosition& position() const { return position_; }
  std::uint8_t heading_end() const { return heading_end_; }
  // +1 if `job` moves the robot towards its pipe's ends[1], -1 towards ends[0], 0 if it does not
  // drive.
  double direction_of(const Job& job) const;
  std::string describe() const { return domain::describe(position_, map_); }

 private:
  const SewerMap& map_;
  domain::RobotPosition position_;
  std::uint8_t heading_end_;
};

}  // namespace sewerplan::executor::detail
