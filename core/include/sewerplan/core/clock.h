// SPDX-License-Identifier: MIT
// Clock: where sewerplan's components get the time, so that tests and simulations control it.
//
// Nothing in the libraries reads the system clock directly: a search's time limit, the executor's
// timeouts and the simulated robot all take a Clock. SteadyClock is the real one; ManualClock only
// moves when told to, for deterministic tests and simulation.
//
//   SteadyClock clock;
//   StopCondition stop = StopCondition::after_seconds(clock, 0.5);
//   ManualClock fake;  fake.advance(2.0);  // fake.now_s() == 2.0
//
// Thread safety: SteadyClock is safe to share between threads; a ManualClock may be read from
// several threads only while nobody advances it.
#pragma once

namespace sewerplan {

class Clock {
 public:
  virtual ~Clock() = default;
  // Seconds since an arbitrary, fixed origin; never decreases.
  virtual double now_s() const = 0;
};

class SteadyClock final : public Clock {
 public:
  double now_s() const override;
};

class ManualClock final : public Clock {
 public:
  explicit ManualClock(double start_s = 0) : now_s_(start_s) {}
  double now_s() const override { return now_s_; }
  // Precondition: seconds >= 0.
  void advance(double seconds) { now_s_ += seconds; }

 private:
  double now_s_;
};

}  // namespace sewerplan
