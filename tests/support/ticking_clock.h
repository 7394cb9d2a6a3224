// SPDX-License-Identifier: MIT
// TickingClock: a fake Clock that moves on by a fixed step every time it is read, so that a test
// can put a deadline a known number of clock reads ahead: "the deadline passes at the n-th check".
//
//   TickingClock clock(1.0);                               // reads 1, 2, 3, ...
//   StopCondition stop = StopCondition::at_deadline(clock, 5);  // fires at the 5th read
//
// Not thread-safe (reading it changes it): for single-threaded tests.
#pragma once

#include "sewerplan/core/clock.h"

namespace sewerplan::testing {

class TickingClock final : public Clock {
 public:
  explicit TickingClock(double step_s) : step_s_(step_s) {}
  double now_s() const override { return now_s_ += step_s_; }
  // How often it was read.
  double reads() const { return now_s_ / step_s_; }

 private:
  double step_s_;
  mutable double now_s_ = 0;
};

}  // namespace sewerplan::testing
