// SPDX-License-Identifier: MIT
// libFuzzer target: random sequences of progress and failure reports through the Replanner
// (executor/replanner.h) on the AIS test bed. Unknown IDs, offsets outside a pipe, NaN and
// infinities must be answered (an error or kInvalidReport), never abort; every plan the Replanner
// answers with must pass the validator from where the robot is, as the executor checks it.
//
// Input: records of one op byte and its fields (FuzzedDataProvider), at most 12 per input.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>

#include "sewerplan/domain/validator.h"
#include "sewerplan/executor/replanner.h"

#include "fuzz_support.h"
#include <fuzzer/FuzzedDataProvider.h>

namespace {

using sewerplan::executor::Failure;
using sewerplan::executor::PlanResponse;

// An offset: mostly along a pipe of `length_m` (and a little beyond), sometimes any double.
double offset(FuzzedDataProvider& in, double length_m) {
  if (in.ConsumeBool()) return in.ConsumeFloatingPoint<double>();
  return in.ConsumeFloatingPointInRange<double>(-1.0, length_m + 1.0);
}

// Pipe and manhole numbers: mostly on the map, sometimes not.
template <class Id>
Id some_id(FuzzedDataProvider& in, std::size_t count) {
  return Id{in.ConsumeIntegralInRange<std::uint32_t>(0, static_cast<std::uint32_t>(count + 2))};
}

double length_of(const sewerplan::SewerMap& map, sewerplan::PipeId pipe) {
  return pipe.index() < map.pipe_count() ? map.pipe(pipe).length_m : 10.0;
}

Failure some_failure(FuzzedDataProvider& in, const sewerplan::SewerMap& map) {
  Failure f;
  f.kind = static_cast<Failure::Kind>(in.ConsumeIntegralInRange<int>(0, 3));
  f.pipe = some_id<sewerplan::PipeId>(in, map.pipe_count());
  f.offset_m = offset(in, length_of(map, f.pipe));
  f.manhole = some_id<sewerplan::ManholeId>(in, map.manhole_count());
  f.from = sewerplan::SlotIndex{in.ConsumeIntegralInRange<std::uint16_t>(0, 5)};
  f.to = sewerplan::SlotIndex{in.ConsumeIntegralInRange<std::uint16_t>(0, 5)};
  f.detail = "fuzz";
  return f;
}

sewerplan::domain::MissionProgress some_progress(FuzzedDataProvider& in,
                                                 const sewerplan::SewerMap& map,
                                                 const sewerplan::Mission& mission) {
  namespace domain = sewerplan::domain;
  domain::MissionProgress p;
  switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0:
      p.position = domain::InManhole{some_id<sewerplan::ManholeId>(in, map.manhole_count())};
      break;
    case 1:
      p.position =
          domain::AtSlot{some_id<sewerplan::ManholeId>(in, map.manhole_count()),
                         sewerplan::SlotIndex{in.ConsumeIntegralInRange<std::uint16_t>(0, 5)}};
      break;
    default: {
      const auto pipe = some_id<sewerplan::PipeId>(in, map.pipe_count());
      p.position = domain::InPipe{pipe, offset(in, length_of(map, pipe))};
    }
  }
  const std::size_t tasks =
      mission.tasks.size() + (in.ConsumeIntegralInRange<int>(0, 9) == 0 ? 1 : 0);
  for (std::size_t i = 0; i < tasks; ++i) p.done.push_back(in.ConsumeBool());
  p.energy_used_wh = in.ConsumeBool() ? in.ConsumeFloatingPoint<double>()
                                      : in.ConsumeFloatingPointInRange<double>(0.0, 300.0);
  return p;
}

// What the executor checks before it runs a plan.
void check_plan(const sewerplan::executor::Replanner& replanner, const PlanResponse& r,
                const sewerplan::SewerMap& map) {
  if (!sewerplan::executor::has_plan(r.decision)) return;
  sewerplan::domain::MissionProgress start = replanner.progress();
  for (const auto& d : replanner.dropped()) start.done[d.task.index()] = true;
  const auto report = sewerplan::domain::validate_plan(r.plan, map, replanner.mission(), start);
  if (!report.valid) {
    std::cerr << "invalid plan after '" << r.reason << "': " << report.error << '\n';
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const sewerplan::fuzz::Testbed& t = sewerplan::fuzz::testbed();
  FuzzedDataProvider in(data, size);
  sewerplan::ManualClock clock;
  sewerplan::executor::Replanner replanner(t.map, t.mission, {.clock = &clock});
  for (int op = 0; op < 12 && in.remaining_bytes() > 0; ++op) {
    switch (in.ConsumeIntegralInRange<int>(0, 2)) {
      case 0: {
        const Failure f = some_failure(in, t.map);
        const bool valid = sewerplan::executor::check_failure(f, t.map).has_value();
        const PlanResponse r = replanner.report_failure(f);
        if (valid == (r.decision == PlanResponse::Decision::kInvalidReport)) std::abort();
        check_plan(replanner, r, t.map);
        break;
      }
      case 1: {
        const auto p = some_progress(in, t.map, replanner.mission());
        (void)replanner.update(p, in.ConsumeIntegralInRange<std::uint8_t>(0, 2));
        break;
      }
      default:
        check_plan(replanner, replanner.plan("fuzz"), t.map);
    }
  }
  return 0;
}
