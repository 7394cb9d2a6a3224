// SPDX-License-Identifier: MIT
#include "dead_reckoning.h"

#include <algorithm>
#include <cmath>

#include "sewerplan/core/map_queries.h"

#include "job_arithmetic.h"

namespace sewerplan::executor::detail {

double DeadReckoning::direction_of(const Job& job) const {
  const double front = heading_end_ == 1 ? 1.0 : -1.0;
  if (std::holds_alternative<DriveForward>(job)) return front;
  if (std::holds_alternative<DriveBackward>(job)) return -front;
  if (const auto* push = std::get_if<Push>(&job)) return push->backward ? -front : front;
  if (const auto* scan = std::get_if<Scan>(&job)) return scan->backward ? -front : front;
  return 0;
}

void DeadReckoning::advance(const Job& job, const hal::JobReport& report) {
  if (const auto* turn = std::get_if<TurnInManhole>(&job)) {
    const auto* at = std::get_if<domain::AtSlot>(&position_);
    // Through a manhole the map lacks (kBySighting): on along the pipe it lies in, as tracked.
    if (!report.ok() || at == nullptr || turn->from_slot == kBySighting) return;
    const Slot& slot = map_.slot(at->manhole, SlotIndex{turn->to_slot});
    position_ =
        domain::InPipe{slot.pipe, domain::end_offset_m(map_.pipe(slot.pipe), slot.pipe_end)};
    heading_end_ = static_cast<std::uint8_t>(1 - slot.pipe_end);
    return;
  }
  if (const auto* enter = std::get_if<EnterPipeFromManhole>(&job)) {
    const auto* in = std::get_if<domain::InManhole>(&position_);
    if (!report.ok() || in == nullptr) return;
    const Slot& slot = map_.slot(in->manhole, SlotIndex{enter->slot});
    position_ =
        domain::InPipe{slot.pipe, domain::end_offset_m(map_.pipe(slot.pipe), slot.pipe_end)};
    heading_end_ = static_cast<std::uint8_t>(1 - slot.pipe_end);
    return;
  }
  const double direction = direction_of(job);
  if (direction == 0 || report.progress_m < 0) return;
  // A drive that got nowhere moves the robot only from right at a pipe's end to its mouth.
  if (report.progress_m == 0 &&
      !(report.ok() && std::holds_alternative<domain::InPipe>(position_))) {
    return;
  }
  if (const auto* at = std::get_if<domain::AtSlot>(&position_)) {
    // Back into the pipe the robot came out of.
    const Slot& slot = map_.slot(at->manhole, at->slot);
    const Pipe& pipe = map_.pipe(slot.pipe);
    const double end = domain::end_offset_m(pipe, slot.pipe_end);
    const double inward = slot.pipe_end == 0 ? 1.0 : -1.0;
    position_ =
        domain::InPipe{slot.pipe, std::clamp(end + inward * report.progress_m, 0.0, pipe.length_m)};
    // A drive to the manhole at the far end that the robot finished is at that end, whatever
    // the odometry (the pipe may be longer or shorter than the map says: core/job.h).
    if (!(ends_at_manhole(job) && report.ok())) return;
  }
  auto* in = std::get_if<domain::InPipe>(&position_);
  if (in == nullptr) return;
  const Pipe& pipe = map_.pipe(in->pipe);
  in->offset_m = std::clamp(in->offset_m + direction * report.progress_m, 0.0, pipe.length_m);
  if (ends_at_manhole(job) && report.ok()) {
    const std::size_t ahead = direction > 0 ? 1 : 0;
    if (pipe.ends[ahead].manhole) in->offset_m = domain::end_offset_m(pipe, ahead);
  }
  // At an end with a manhole, the robot is at that manhole's mouth; unless the drive failed there
  // (against a blind end the world has where the map has a manhole): then it stopped short of it,
  // in the pipe.
  for (std::size_t e = 0; e < 2; ++e) {
    const double end = domain::end_offset_m(pipe, e);
    const bool towards = (e == 1) == (direction > 0);
    if (!towards || std::abs(in->offset_m - end) > 1e-6 || !pipe.ends[e].manhole) continue;
    if (!report.ok()) {
      in->offset_m = std::clamp(end - direction * 2 * kBlockageAhead_m, 0.0, pipe.length_m);
      return;
    }
    position_ = domain::AtSlot{*pipe.ends[e].manhole, pipe.ends[e].slot};
    return;
  }
}

}  // namespace sewerplan::executor::detail
